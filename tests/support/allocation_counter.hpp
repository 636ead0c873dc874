// Counts heap allocations, to check that hot paths allocate nothing. Link
// support/allocation_counter.cpp into the test: it replaces the global operator new.
#pragma once

namespace fuzzygait::testing {

long allocation_count();

}  // namespace fuzzygait::testing
