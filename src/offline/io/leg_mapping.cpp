// Leg mappings: the JSON file naming a skeleton's leg joints, the built-in names, and finding
// the legs in a skeleton.
#include <algorithm>
#include <array>
#include <cstddef>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "fuzzygait/io/mocap.hpp"
#include "offline/io/leg_chains.hpp"
#include "runtime/common/json.hpp"

namespace fuzzygait::io {
namespace {

using common::json::Value;

constexpr std::array<const char*, 2> kSideKeys = {"left", "right"};
constexpr std::array<const char*, 4> kPartKeys = {"hip", "knee", "ankle", "toe"};
constexpr std::array<std::array<const char*, 3>, 2> kSidePrefixes = {
    {{"Left", "L", "l"}, {"Right", "R", "r"}}};
// The built-in names of each part, in the order they are tried (the reference extractor's).
const std::array<std::vector<const char*>, 4> kAliases = {{{"UpLeg", "Hip", "Thigh", "femur"},
                                                           {"Leg", "Knee", "Shin", "tibia"},
                                                           {"Foot", "Ankle", "foot"},
                                                           {"ToeBase", "Toe", "toes"}}};

std::string& part_of(LegJoints& leg, std::size_t part) {
  const std::array<std::string*, 4> fields = {&leg.hip, &leg.knee, &leg.ankle, &leg.toe};
  return *fields[part];
}
const std::string& part_of(const LegJoints& leg, std::size_t part) {
  const std::array<const std::string*, 4> fields = {&leg.hip, &leg.knee, &leg.ankle, &leg.toe};
  return *fields[part];
}

// The joint's name as a message quotes it.
std::string quoted(const BvhClip& bvh, int joint) {
  const BvhJoint& j = bvh.joints[static_cast<std::size_t>(joint)];
  return j.end_site ? "the End Site of line " + std::to_string(j.line) : "'" + j.name + "'";
}

bool is_below(const BvhClip& bvh, int joint, int ancestor) {
  for (int j = bvh.joints[static_cast<std::size_t>(joint)].parent; j >= 0;
       j = bvh.joints[static_cast<std::size_t>(j)].parent) {
    if (j == ancestor) return true;
  }
  return false;
}

// The joint's first child (a joint or an End Site), or -1.
int first_child(const BvhClip& bvh, int joint) {
  for (std::size_t i = 0; i < bvh.joints.size(); ++i) {
    if (bvh.joints[i].parent == joint) return static_cast<int>(i);
  }
  return -1;
}

std::string text_member(const Value& object, const char* key, const std::string& field,
                        const std::string& source, bool required) {
  const Value* v = object.find(key);
  if (!v) {
    if (required) throw MocapError(source, object.line, "expected the field '" + field + "'");
    return {};
  }
  if (v->kind != Value::Kind::String || v->string.empty()) {
    throw MocapError(source, v->line,
                     "expected a joint name (a non-empty string) in '" + field + "' found " +
                         common::json::kind_name(v->kind));
  }
  return v->string;
}

void only_keys(const Value& object, std::initializer_list<const char*> keys,
               const std::string& where, const std::string& source) {
  for (const auto& [key, value] : object.object) {
    bool known = false;
    for (const char* k : keys)
      known = known || key == k;
    if (!known) {
      std::string list;
      for (const char* k : keys)
        list += (list.empty() ? "'" : ", '") + std::string(k) + "'";
      throw MocapError(source, value.line,
                       "expected " + list + " in " + where + " found '" + key + "'");
    }
  }
}

}  // namespace

LegMapping read_leg_mapping(std::string_view json, std::string_view source) {
  const std::string where(source);
  const Value root = common::json::parse(json, where);
  if (root.kind != Value::Kind::Object) {
    throw MocapError(
        where, root.line,
        std::string("expected a JSON object found ") + common::json::kind_name(root.kind));
  }
  only_keys(root, {"root", "left", "right"}, "the mapping", where);
  LegMapping mapping;
  mapping.source = where;
  mapping.root = text_member(root, "root", "root", where, false);
  for (std::size_t side = 0; side < 2; ++side) {
    const char* key = kSideKeys[side];
    const Value* leg = root.find(key);
    if (!leg) throw MocapError(where, root.line, "expected the field '" + std::string(key) + "'");
    if (leg->kind != Value::Kind::Object) {
      throw MocapError(where, leg->line,
                       "expected an object naming hip, knee, ankle and toe in '" +
                           std::string(key) + "' found " + common::json::kind_name(leg->kind));
    }
    only_keys(*leg, {"hip", "knee", "ankle", "toe"}, "'" + std::string(key) + "'", where);
    for (std::size_t part = 0; part < kPartKeys.size(); ++part) {
      const std::string field = std::string(key) + "." + kPartKeys[part];
      part_of(mapping.legs[side], part) =
          text_member(*leg, kPartKeys[part], field, where, part != 3);
    }
  }
  return mapping;
}

LegMapping read_leg_mapping_file(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw MocapError(path.string(), 0, "is a directory, not a mapping file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MocapError(path.string(), 0, "cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  return read_leg_mapping(text.str(), path.string());
}

namespace detail {

SkeletonLegs find_legs(const BvhClip& bvh, std::string_view source, const LegMapping* mapping) {
  const std::string clip(source);
  const bool mapped = mapping != nullptr;
  const std::string map_source = mapped && !mapping->source.empty() ? mapping->source : "mapping";
  SkeletonLegs found;
  if (mapped && !mapping->root.empty()) {
    found.root = bvh.find(mapping->root);
    if (found.root < 0) {
      throw MocapError(map_source, 0, "root: no joint '" + mapping->root + "' in " + clip);
    }
  } else {
    found.root = std::max(bvh.find("Hips"), 0);
  }
  for (std::size_t side = 0; side < 2; ++side) {
    const std::string side_name = side == 0 ? "left" : "right";
    detail::LegChain& chain = found.legs[side];
    std::array<int*, 4> joints = {&chain.hip, &chain.knee, &chain.ankle, &chain.toe};
    for (std::size_t part = 0; part < joints.size(); ++part) {
      const std::string field = side_name + "." + kPartKeys[part];
      if (mapped) {
        const std::string& name = part_of(mapping->legs[side], part);
        if (!name.empty()) {
          *joints[part] = bvh.find(name);
          if (*joints[part] < 0) {
            throw MocapError(map_source, 0, field + ": no joint '" + name + "' in " + clip);
          }
          continue;
        }
        if (part < 3) throw MocapError(map_source, 0, "expected the field '" + field + "'");
      } else {
        for (const char* alias : kAliases[part]) {
          for (const char* prefix : kSidePrefixes[side]) {
            if (*joints[part] < 0) *joints[part] = bvh.find(std::string(prefix) + alias);
          }
        }
      }
      if (*joints[part] >= 0) continue;
      if (part == 3) {  // no toe joint named or found: the ankle's first child stands for it
        chain.toe = first_child(bvh, chain.ankle);
        if (chain.toe >= 0) {
          found.notes.push_back("no " + side_name + " toe joint " +
                                (mapped ? std::string("named") : std::string("found")) + ": " +
                                quoted(bvh, chain.toe) + ", the first child of the ankle " +
                                quoted(bvh, chain.ankle) + ", stands for the toe base");
          continue;
        }
        if (mapped) {
          throw MocapError(map_source, 0,
                           field + ": none given and the ankle " + quoted(bvh, chain.ankle) +
                               " has no child to stand for it in " + clip);
        }
      }
      std::string tried;
      for (const char* alias : kAliases[part]) {
        for (const char* prefix : kSidePrefixes[side])
          tried += (tried.empty() ? "" : ", ") + std::string(prefix) + alias;
      }
      throw MocapError(clip, 0,
                       "expected a " + side_name + " " + kPartKeys[part] + " joint (one of " +
                           tried + ") found none; name the legs' joints in a mapping file (--map)");
    }
    for (std::size_t part = 1; part < joints.size(); ++part) {
      if (!is_below(bvh, *joints[part], *joints[part - 1])) {
        throw MocapError(mapped ? map_source : clip, 0,
                         "expected the " + side_name + " " + kPartKeys[part] + " " +
                             quoted(bvh, *joints[part]) + " below the " + kPartKeys[part - 1] +
                             " " + quoted(bvh, *joints[part - 1]) + " in the hierarchy of " + clip);
      }
    }
    chain.tip =
        bvh.joints[static_cast<std::size_t>(chain.toe)].end_site ? -1 : first_child(bvh, chain.toe);
  }
  const LegChain& l = found.legs[0];
  const LegChain& r = found.legs[1];
  for (int a : {l.hip, l.knee, l.ankle, l.toe}) {
    for (int b : {r.hip, r.knee, r.ankle, r.toe}) {
      if (a == b) {
        throw MocapError(
            mapped ? map_source : clip, 0,
            "expected two legs found the joint " + quoted(bvh, a) + " in both in " + clip);
      }
    }
  }
  return found;
}

}  // namespace detail
}  // namespace fuzzygait::io
