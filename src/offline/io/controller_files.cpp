#include "fuzzygait/io/controller_files.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/io/files.hpp"
#include "fuzzygait/rig/rig.hpp"

namespace fuzzygait::io {

void save_controller_set(const gait::ControllerSet& set, const std::filesystem::path& directory) {
  std::filesystem::create_directories(directory);
  nlohmann::ordered_json manifest;
  manifest["name"] = set.name;
  manifest["description"] = set.description;
  manifest["inertia_s"] = set.inertia;
  manifest["pelvis_tilt_deg"] = std::round(rig::degrees(set.pelvis_tilt) * 1e6) / 1e6;
  if (set.swing_knee_reference_sweep > 0.0) {
    manifest["swing_knee_reference_sweep_deg"] =
        std::round(rig::degrees(set.swing_knee_reference_sweep) * 1e6) / 1e6;
  }
  manifest["shortest_step_leg_lengths"] = set.shortest_step;
  nlohmann::ordered_json files;
  for (int s = 0; s < gait::kSlotCount; ++s) {
    const std::string name = std::string(gait::slot_name(s)) + ".fll";
    files[std::string(gait::slot_name(s))] = name;
    write_file(directory / name,
               fuzzy::write_fll(set.controllers.at(static_cast<std::size_t>(s)).engine()));
  }
  manifest["controllers"] = files;
  write_file(directory / "manifest.json", manifest.dump(2) + "\n");
}

}  // namespace fuzzygait::io
