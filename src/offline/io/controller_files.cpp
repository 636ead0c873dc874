#include "fuzzygait/io/controller_files.hpp"

#include <array>
#include <cmath>
#include <nlohmann/json.hpp>

#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/io/files.hpp"
#include "fuzzygait/rig/rig.hpp"

namespace fuzzygait::io {

std::vector<SetFile> controller_set_files(const gait::ControllerSet& set) {
  std::vector<SetFile> written;
  nlohmann::ordered_json manifest;
  manifest["name"] = set.name;
  manifest["description"] = set.description;
  // The manifest's numbers, as the reader's table names them (to a millionth, so that degrees
  // held in radians come back as written).
  for (const gait::ControllerSet::ManifestNumber& n : gait::ControllerSet::manifest_numbers())
    manifest[n.key] = std::round(n.get(set) * 1e6) / 1e6;
  if (set.body && set.body_step_length) {
    // To a tenth of a millimetre.
    auto length = [](double metres) { return std::round(metres * 1e4) / 1e4; };
    const rig::Segments& b = *set.body;
    nlohmann::ordered_json body;
    body["thigh_m"] = length(b.thigh);
    body["shank_m"] = length(b.shank);
    body["ankle_height_m"] = length(b.ankle_height);
    body["heel_m"] = length(b.heel);
    body["ball_m"] = length(b.ball);
    body["toe_m"] = length(b.toe);
    body["step_length_m"] = length(*set.body_step_length);
    if (set.body_speed) body["speed_m_s"] = std::round(*set.body_speed * 1e4) / 1e4;
    manifest["body"] = body;
  }
  nlohmann::ordered_json files;
  for (int s = 0; s < gait::kSlotCount; ++s) {
    const std::string name = std::string(gait::slot_name(s)) + ".fll";
    files[std::string(gait::slot_name(s))] = name;
    written.push_back(
        {name, fuzzy::write_fll(set.controllers.at(static_cast<std::size_t>(s)).engine())});
  }
  manifest["controllers"] = files;
  if (set.stride) {
    manifest["stride"] = "stride.fll";
    written.push_back({"stride.fll", fuzzy::write_fll(set.stride->engine())});
  }
  nlohmann::ordered_json upper_body;
  for (int p = 0; p < gait::kUpperBodyCount; ++p) {
    const auto& controller = set.upper_body[static_cast<std::size_t>(p)];
    if (!controller) continue;
    const std::string part(gait::upper_body_name(static_cast<gait::UpperBody>(p)));
    upper_body[part] = "upper_body_" + part + ".fll";
    written.push_back({"upper_body_" + part + ".fll", fuzzy::write_fll(controller->engine())});
  }
  if (!upper_body.empty()) manifest["upper_body"] = upper_body;
  // The terrain words: each kind of ground's words, and its files named GROUND_SLOT_WORD.fll.
  nlohmann::ordered_json terrain;
  constexpr std::array<const char*, gait::kGroundCount> kGroundNames = {"slopes", "stairs"};
  for (std::size_t g = 0; g < set.ground.size(); ++g) {
    const gait::ControllerSet::GroundWords& words = set.ground[g];
    if (words.empty()) continue;
    nlohmann::ordered_json ground;
    nlohmann::ordered_json peaks;
    nlohmann::ordered_json knees;
    nlohmann::json ascent = nlohmann::json::array();
    for (std::size_t w = 0; w < words.words.size(); ++w) {
      peaks[words.words[w]] = words.peaks[w];
      if (words.ascent[w]) ascent.push_back(words.words[w]);
      if (words.landing_knee[w] > 0.0) {
        knees[words.words[w]] = std::round(rig::degrees(words.landing_knee[w]) * 1e6) / 1e6;
      }
    }
    ground["incline_deg"] = peaks;
    if (!ascent.empty()) ground["ascent"] = ascent;
    if (!knees.empty()) ground["landing_knee_deg"] = knees;
    nlohmann::ordered_json by_slot;
    for (int s = 0; s < gait::kSlotCount; ++s) {
      nlohmann::ordered_json by_word;
      for (std::size_t w = 0; w < words.words.size(); ++w) {
        const int c = words.of_slot[static_cast<std::size_t>(s)][w];
        if (c < 0) continue;
        const std::string name = std::string(kGroundNames[g]) + "_" +
                                 std::string(gait::slot_name(s)) + "_" + words.words[w] + ".fll";
        by_word[words.words[w]] = name;
        written.push_back(
            {name,
             fuzzy::write_fll(set.terrain_controllers.at(static_cast<std::size_t>(c)).engine())});
      }
      if (!by_word.empty()) by_slot[std::string(gait::slot_name(s))] = by_word;
    }
    if (!by_slot.empty()) ground["controllers"] = by_slot;
    terrain[kGroundNames[g]] = ground;
  }
  if (!terrain.empty()) manifest["terrain"] = terrain;
  written.push_back({"manifest.json", manifest.dump(2) + "\n"});
  return written;
}

void save_controller_set(const gait::ControllerSet& set, const std::filesystem::path& directory) {
  std::filesystem::create_directories(directory);
  for (const SetFile& file : controller_set_files(set))
    write_file(directory / file.name, file.text);
}

}  // namespace fuzzygait::io
