// fuzzygait: command-line front end of the library.
#include <exception>
#include <iostream>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"fuzzygait: real-time procedural gait animation driven by fuzzy controllers"};
  app.require_subcommand(1);
  fuzzygait::cli::add_walk_command(app);
  fuzzygait::cli::add_eval_command(app);
  fuzzygait::cli::add_fuzzy_command(app);
  fuzzygait::cli::add_tune_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "fuzzygait: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
