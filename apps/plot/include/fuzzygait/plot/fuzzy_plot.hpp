// Drawings of fuzzy engines: every variable's terms, the picture an animator tunes by, and how
// each output answers its inputs.
#pragma once

#include "fuzzygait/fuzzy/engine.hpp"
#include "fuzzygait/plot/svg.hpp"

namespace fuzzygait::plot {

struct EnginePlotOptions {
  int curve_samples = 301;   // points along each membership function and input-output curve
  int surface_samples = 61;  // grid points per input axis of a two-input surface
  int columns = 2;           // panels per row
};

// A figure of the engine. One panel per variable with every term's membership function labelled
// with its name; Takagi-Sugeno Constant terms are stems at their value, Linear and Function terms
// are listed as formulas. With one input, each output's curve against it; with two, each output's
// surface as a heat map with contour lines; with more, a note says why neither is drawn. The
// rules are listed under the panels. An engine that cannot be evaluated gets its terms only, and
// its problems in a note. Throws std::invalid_argument when an option is out of range.
svg::Figure plot_engine(const fuzzy::Engine& engine, const EnginePlotOptions& options = {});

}  // namespace fuzzygait::plot
