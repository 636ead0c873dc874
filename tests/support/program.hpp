// Runs the fuzzygait program (FUZZYGAIT_CLI) with arguments through the shell, for the tests of
// the command line: its exit status and everything it printed (standard output and error).
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <memory>
#include <string>

namespace fuzzygait::test {

struct ProgramRun {
  int status;
  std::string output;
};

inline ProgramRun run_program(const std::string& arguments) {
  const std::string command = std::string("\"") + FUZZYGAIT_CLI + "\" " + arguments + " 2>&1";
  ProgramRun result{-1, {}};
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  while (const std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe.get())) {
    result.output.append(buffer.data(), n);
  }
  const int status = pclose(pipe.release());
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace fuzzygait::test
