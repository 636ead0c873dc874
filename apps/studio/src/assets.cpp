#include "assets.hpp"

#include <map>
#include <string>

namespace fuzzygait::studio::detail {
namespace {

std::string_view content_type(std::string_view path) {
  const auto ends_with = [&](std::string_view end) {
    return path.size() >= end.size() && path.substr(path.size() - end.size()) == end;
  };
  if (ends_with(".html")) return "text/html; charset=utf-8";
  if (ends_with(".js")) return "text/javascript; charset=utf-8";
  if (ends_with(".css")) return "text/css; charset=utf-8";
  if (ends_with(".json")) return "application/json; charset=utf-8";
  if (ends_with(".svg")) return "image/svg+xml; charset=utf-8";
  return "text/plain; charset=utf-8";
}

std::map<std::string, Asset, std::less<>> make_assets() {
  std::map<std::string, Asset, std::less<>> assets;
  for (const EmbeddedFile& f : page::embedded_files()) {
    assets["/" + std::string(f.path)] = {f.text, content_type(f.path)};
  }
  for (const EmbeddedFile& f : vendor::embedded_files()) {
    assets["/vendor/" + std::string(f.path)] = {f.text, content_type(f.path)};
  }
  if (const auto index = assets.find("/index.html"); index != assets.end()) {
    assets["/"] = index->second;
  }
  return assets;
}

}  // namespace

const Asset* find_asset(std::string_view url_path) {
  static const std::map<std::string, Asset, std::less<>> assets = make_assets();
  const auto it = assets.find(url_path);
  return it == assets.end() ? nullptr : &it->second;
}

}  // namespace fuzzygait::studio::detail
