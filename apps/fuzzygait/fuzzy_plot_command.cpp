// `fuzzygait fuzzy plot`: an engine's terms, curves and surfaces as an SVG figure.
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/plot/fuzzy_plot.hpp"

namespace fuzzygait::cli {

void add_fuzzy_plot_command(CLI::App& fuzzy) {
  struct Options {
    std::string engine_path;
    std::string output_path;
    plot::EnginePlotOptions plot;
  };
  auto options = std::make_shared<Options>();
  CLI::App* plot = fuzzy.add_subcommand(
      "plot", "Draw an engine as an SVG figure: its terms, curves or surfaces, and rules");
  plot->footer(
      "The figure has a panel per variable with every term's membership function, labelled\n"
      "with its name (Takagi-Sugeno constants are stems at their value; Linear and Function\n"
      "terms are written out). With one input, each output is drawn against it; with two, each\n"
      "output is a shaded surface with contour lines. The rules are listed underneath.\n"
      "Example: fuzzygait fuzzy plot controllers/paper/ease_in_out.fll -o ease_in_out.svg");
  plot->add_option("engine", options->engine_path, "Engine in FLL")->required();
  plot->add_option("-o,--output", options->output_path, "SVG file to write (default: stdout)");
  plot->add_option("--grid", options->plot.surface_samples,
                   "Grid points per input axis of two-input surfaces")
      ->check(CLI::Range(2, 1000))
      ->capture_default_str();
  plot->add_option("--samples", options->plot.curve_samples,
                   "Points along each membership function and input-output curve")
      ->check(CLI::Range(2, 100000))
      ->capture_default_str();
  plot->add_option("--columns", options->plot.columns, "Panels per row")
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  plot->callback([options]() {
    const plot::svg::Figure figure =
        plot::plot_engine(fuzzy::read_fll_file(options->engine_path), options->plot);
    if (options->output_path.empty() || options->output_path == "-") {
      std::cout << figure.svg();
    } else {
      figure.save(options->output_path);
    }
  });
}

}  // namespace fuzzygait::cli
