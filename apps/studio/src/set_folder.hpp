// Writing a saved set into its folder of the workspace without following a symbolic link, even
// one put there after the studio looked: the folder is opened once (O_NOFOLLOW) and every file is
// written relative to it, to a new file renamed into place.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "fuzzygait/io/controller_files.hpp"

namespace fuzzygait::studio::detail {

// Writes `files` into WORKSPACE/NAME (made when missing; the workspace too), replacing files of
// the same names, and removes the .fll files the folder's previous manifest.json named that
// `files` no longer has. A link in place of the folder is refused with RequestError 422 naming
// "name"; one in place of a file is replaced, never written through. What the disk refuses is a
// RequestError 500.
void write_set_folder(const std::filesystem::path& workspace, const std::string& name,
                      const std::vector<io::SetFile>& files);

// The .fll files a manifest's text names (the studio's own earlier save of a set).
std::vector<std::string> manifest_fll_files(const std::string& manifest_text);

}  // namespace fuzzygait::studio::detail
