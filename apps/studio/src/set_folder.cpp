#include "set_folder.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <functional>
#include <nlohmann/json.hpp>

#include "fuzzygait/studio/studio.hpp"

namespace fuzzygait::studio::detail {
namespace {

// A file descriptor closed when it goes.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

[[noreturn]] void disk_refused(const std::filesystem::path& path, const std::string& doing) {
  throw RequestError(
      500, "name", "cannot save to " + path.string() + ": " + doing + ": " + std::strerror(errno));
}

// The text of `name` in the folder, "" when it is missing or not a plain file.
std::string read_plain_file(int folder, const char* name) {
  const Descriptor file(::openat(folder, name, O_RDONLY | O_NOFOLLOW | O_CLOEXEC));
  std::string text;
  if (file.get() < 0) return text;
  std::array<char, 8192> buffer;
  for (;;) {
    const ssize_t n = ::read(file.get(), buffer.data(), buffer.size());
    if (n <= 0) break;
    text.append(buffer.data(), static_cast<std::size_t>(n));
  }
  return text;
}

void write_all(int fd, const std::string& text, const std::filesystem::path& path) {
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) disk_refused(path, "writing");
    written += static_cast<std::size_t>(n);
  }
}

}  // namespace

std::vector<std::string> manifest_fll_files(const std::string& manifest_text) {
  std::vector<std::string> files;
  const nlohmann::json manifest = nlohmann::json::parse(manifest_text, nullptr, false);
  const std::function<void(const nlohmann::json&)> collect = [&](const nlohmann::json& value) {
    if (value.is_string()) {
      const std::string name = value.get<std::string>();
      if (name.size() > 4 && name.ends_with(".fll") && name.find('/') == std::string::npos)
        files.push_back(name);
    } else if (value.is_structured()) {
      for (const nlohmann::json& item : value)
        collect(item);
    }
  };
  if (!manifest.is_discarded()) collect(manifest);
  return files;
}

void write_set_folder(const std::filesystem::path& workspace, const std::string& name,
                      const std::vector<io::SetFile>& files) {
  const std::filesystem::path folder_path = workspace / name;
  std::error_code made_error;
  std::filesystem::create_directories(workspace, made_error);
  const Descriptor root(::open(workspace.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (root.get() < 0) disk_refused(workspace, "opening the workspace");
  if (::mkdirat(root.get(), name.c_str(), 0755) != 0 && errno != EEXIST)
    disk_refused(folder_path, "making the folder");
  const Descriptor folder(
      ::openat(root.get(), name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
  if (folder.get() < 0) {
    if (errno == ELOOP || errno == ENOTDIR) {
      throw RequestError(422, "name",
                         "cannot save to " + folder_path.string() +
                             ": it is a symbolic link or not a folder (a save writes only into "
                             "the workspace)");
    }
    disk_refused(folder_path, "opening the folder");
  }
  const std::vector<std::string> before =
      manifest_fll_files(read_plain_file(folder.get(), "manifest.json"));
  for (const io::SetFile& file : files) {
    // A new file renamed over the old name: a link planted there is replaced, not followed.
    const std::string draft = "." + file.name + ".saving";
    ::unlinkat(folder.get(), draft.c_str(), 0);
    const Descriptor out(::openat(folder.get(), draft.c_str(),
                                  O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644));
    if (out.get() < 0) disk_refused(folder_path / file.name, "creating");
    write_all(out.get(), file.text, folder_path / file.name);
    if (::renameat(folder.get(), draft.c_str(), folder.get(), file.name.c_str()) != 0)
      disk_refused(folder_path / file.name, "renaming into place");
  }
  // Files of the set saved there before that this one has not (terrain words): those go, when
  // they are plain files; other files stay.
  for (const std::string& old : before) {
    const bool kept = std::any_of(files.begin(), files.end(),
                                  [&](const io::SetFile& file) { return file.name == old; });
    struct stat status {};
    if (!kept && ::fstatat(folder.get(), old.c_str(), &status, AT_SYMLINK_NOFOLLOW) == 0 &&
        S_ISREG(status.st_mode)) {
      ::unlinkat(folder.get(), old.c_str(), 0);
    }
  }
}

}  // namespace fuzzygait::studio::detail
