#include "fuzzygait/io/files.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>

namespace fuzzygait::io {
namespace {

// `error`: the errno of the failed call, or 0 when the system gave no reason.
[[noreturn]] void fail(const std::filesystem::path& path, const char* what, int error) {
  throw std::runtime_error(path.string() + ": " + what +
                           (error != 0 ? " (" + std::string(std::strerror(error)) + ")" : ""));
}

}  // namespace

void write_file(const std::filesystem::path& path,
                const std::function<void(std::ostream&)>& write) {
  errno = 0;
  std::ofstream out(path, std::ios::binary);
  if (!out) fail(path, "cannot open for writing", errno);
  errno = 0;
  write(out);
  // The reason of a failed write, taken before closing can overwrite it.
  const int write_error = out.fail() ? errno : 0;
  errno = 0;
  out.close();  // flushes: a full disk shows here
  if (out.fail()) fail(path, "cannot write", write_error != 0 ? write_error : errno);
}

void write_file(const std::filesystem::path& path, std::string_view text) {
  write_file(path, [text](std::ostream& out) {
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
  });
}

}  // namespace fuzzygait::io
