#include "request.hpp"

#include <algorithm>
#include <cmath>

#include "runtime/common/format.hpp"

namespace fuzzygait::studio::detail {
namespace {

using common::number_text;

const nlohmann::json* find(const nlohmann::json& request, std::string_view field) {
  const auto it = request.find(field);
  return it == request.end() ? nullptr : &*it;
}

const nlohmann::json& required(const nlohmann::json& request, std::string_view field) {
  const nlohmann::json* value = find(request, field);
  if (!value) {
    throw RequestError(400, std::string(field), "'" + std::string(field) + "' is missing");
  }
  return *value;
}

double as_number(const nlohmann::json& value, std::string_view field, double low, double high) {
  const std::string name(field);
  if (!value.is_number()) {
    throw RequestError(400, name, "'" + name + "' must be a number, found " + value.type_name());
  }
  const double x = value.get<double>();
  if (!std::isfinite(x) || std::abs(x) > Limits::kLargestValue) {
    throw RequestError(422, name,
                       "'" + name + "' must be a finite number within " +
                           number_text(Limits::kLargestValue) + " of 0, got " + number_text(x));
  }
  if (!(x >= low && x <= high)) {
    throw RequestError(422, name,
                       "'" + name + "' must be between " + number_text(low) + " and " +
                           number_text(high) + ", got " + number_text(x));
  }
  return x;
}

std::string as_string(const nlohmann::json& value, std::string_view field) {
  const std::string name(field);
  if (!value.is_string()) {
    throw RequestError(400, name, "'" + name + "' must be a string, found " + value.type_name());
  }
  std::string text = value.get<std::string>();
  if (text.size() > Limits::kLongestText) {
    throw RequestError(
        422, name,
        "'" + name + "' is longer than " + std::to_string(Limits::kLongestText) + " characters");
  }
  return text;
}

}  // namespace

void check_fields(const nlohmann::json& request, std::initializer_list<std::string_view> allowed) {
  if (!request.is_object()) {
    throw RequestError(
        400, "body",
        std::string("the request must be a JSON object, found ") + request.type_name());
  }
  for (const auto& [key, value] : request.items()) {
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      std::string known;
      for (std::string_view a : allowed)
        known += (known.empty() ? "" : ", ") + std::string(a);
      throw RequestError(400, key, "unknown field '" + key + "' (known: " + known + ")");
    }
  }
}

double number_field(const nlohmann::json& request, std::string_view field, double low,
                    double high) {
  return as_number(required(request, field), field, low, high);
}

std::optional<double> optional_number(const nlohmann::json& request, std::string_view field,
                                      double low, double high) {
  const nlohmann::json* value = find(request, field);
  if (!value) return std::nullopt;
  return as_number(*value, field, low, high);
}

int integer_field(const nlohmann::json& request, std::string_view field, int low, int high) {
  const nlohmann::json& value = required(request, field);
  const std::string name(field);
  if (!value.is_number_integer()) {
    throw RequestError(400, name,
                       "'" + name + "' must be a whole number, found " +
                           (value.is_number() ? std::string("a fraction") : value.type_name()));
  }
  // Compared as a double: a whole number past 64 bits or below -2^63 stays out of range.
  const double n = value.get<double>();
  if (!(n >= low && n <= high)) {
    throw RequestError(422, name,
                       "'" + name + "' must be between " + std::to_string(low) + " and " +
                           std::to_string(high) + ", got " + value.dump());
  }
  return static_cast<int>(n);
}

std::string string_field(const nlohmann::json& request, std::string_view field) {
  return as_string(required(request, field), field);
}

std::optional<std::string> optional_string(const nlohmann::json& request, std::string_view field) {
  const nlohmann::json* value = find(request, field);
  if (!value) return std::nullopt;
  return as_string(*value, field);
}

bool optional_flag(const nlohmann::json& request, std::string_view field) {
  const nlohmann::json* value = find(request, field);
  if (!value) return false;
  if (!value->is_boolean()) {
    const std::string name(field);
    throw RequestError(400, name,
                       "'" + name + "' must be true or false, found " + value->type_name());
  }
  return value->get<bool>();
}

std::vector<path::GroundPoint> points_field(const nlohmann::json& request, std::string_view field,
                                            std::size_t fewest, std::size_t most) {
  const nlohmann::json& value = required(request, field);
  const std::string name(field);
  if (!value.is_array()) {
    throw RequestError(
        400, name, "'" + name + "' must be a list of [x, z] points, found " + value.type_name());
  }
  if (value.size() < fewest || value.size() > most) {
    throw RequestError(422, name,
                       "'" + name + "' must have " + std::to_string(fewest) + " to " +
                           std::to_string(most) + " points, got " + std::to_string(value.size()));
  }
  std::vector<path::GroundPoint> points;
  points.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) {
    const nlohmann::json& p = value[i];
    const std::string which = name + " point " + std::to_string(i + 1);
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number()) {
      throw RequestError(400, name, which + " must be [x, z], two numbers, found " + p.dump());
    }
    const double x = p[0].get<double>();
    const double z = p[1].get<double>();
    if (!std::isfinite(x) || !std::isfinite(z) || std::abs(x) > Limits::kLargestValue ||
        std::abs(z) > Limits::kLargestValue) {
      throw RequestError(422, name,
                         which + " must lie within " + number_text(Limits::kLargestValue) +
                             " m of the origin, got " + p.dump());
    }
    points.push_back({x, z});
  }
  return points;
}

bool is_plain_name(std::string_view name) {
  return !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
           c == '_';
  });
}

}  // namespace fuzzygait::studio::detail
