// libFuzzer target for the formula compiler of Function terms, fuzzygait::fuzzy::compile_formula.
//
// Contract: any text either compiles or is refused with std::invalid_argument. A compiled
// program is well formed (slots in range, the stack it claims is enough, exactly checked by
// AddressSanitizer) and evaluates deterministically, including on NaN and infinite values.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_check.hpp"
#include "fuzzygait/fuzzy/formula.hpp"

namespace {

using namespace fuzzygait::fuzzy;
using fuzzygait::fuzz::fail;

double evaluate_exactly_sized(const FormulaProgram& program, const std::vector<double>& values) {
  // Heap storage of exactly stack_size doubles: an overflow is an AddressSanitizer report.
  std::vector<double> stack(program.stack_size);
  return evaluate_formula(program, values.data(), stack.data());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    to_postfix(text);
  } catch (const std::invalid_argument&) {
  } catch (const std::exception& e) {
    fail("to_postfix threw something other than std::invalid_argument", e.what());
  }
  FormulaProgram program;
  try {
    program = compile_formula(text);
  } catch (const std::invalid_argument&) {
    return 0;
  } catch (const std::exception& e) {
    fail("compile_formula threw something other than std::invalid_argument", e.what());
  }
  if (program.code.empty() || program.stack_size == 0) fail("an empty program compiled");
  for (const FormulaInstruction& instruction : program.code) {
    if (instruction.kind == FormulaInstruction::Kind::Variable &&
        instruction.slot >= program.variables.size()) {
      fail("a variable slot is out of range");
    }
  }
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double probe : {0.0, 0.5, -1.0, 1e308, nan, inf, -inf}) {
    std::vector<double> values(program.variables.size());
    for (std::size_t i = 0; i < values.size(); ++i)
      values[i] = probe * static_cast<double>(i + 1);
    const double first = evaluate_exactly_sized(program, values);
    const double second = evaluate_exactly_sized(program, values);
    if (std::memcmp(&first, &second, sizeof first) != 0) {
      fail("evaluating twice gives different bits", program.text);
    }
  }
  return 0;
}
