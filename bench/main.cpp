// fuzzygait-bench: performance comparisons with reference implementations. It links fuzzylite
// (GPL) as the reference, so it stays a separate program and is never installed.
#include <exception>
#include <iostream>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"fuzzygait-bench: fuzzygait's speed against reference implementations"};
  app.require_subcommand(1);
  fuzzygait::bench::add_fuzzy_command(app);
  fuzzygait::bench::add_gait_command(app);
  fuzzygait::bench::add_crowd_command(app);
  fuzzygait::bench::add_terrain_command(app);
  fuzzygait::bench::add_body_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "fuzzygait-bench: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
