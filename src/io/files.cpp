#include "fuzzygait/io/files.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>

namespace fuzzygait::io {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const char* what) {
  const int error = errno;
  throw std::runtime_error(path.string() + ": " + what +
                           (error != 0 ? " (" + std::string(std::strerror(error)) + ")" : ""));
}

}  // namespace

void write_file(const std::filesystem::path& path,
                const std::function<void(std::ostream&)>& write) {
  errno = 0;
  std::ofstream out(path, std::ios::binary);
  if (!out) fail(path, "cannot create the file");
  write(out);
  out.close();  // flushes: a full disk shows here
  if (out.fail()) fail(path, "cannot write");
}

void write_file(const std::filesystem::path& path, std::string_view text) {
  write_file(path, [text](std::ostream& out) {
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
  });
}

}  // namespace fuzzygait::io
