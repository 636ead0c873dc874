// Reading a request's fields: each refusal is a RequestError naming the field.
#pragma once

#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fuzzygait/path/path.hpp"
#include "fuzzygait/studio/studio.hpp"

namespace fuzzygait::studio::detail {

// 400 unless `request` is a JSON object whose keys are all in `allowed`.
void check_fields(const nlohmann::json& request, std::initializer_list<std::string_view> allowed);

// The field as a finite number (400 when missing or not a number; 422 when beyond
// Limits::kLargestValue or outside [low, high], naming the range).
double number_field(const nlohmann::json& request, std::string_view field,
                    double low = -Limits::kLargestValue, double high = Limits::kLargestValue);
std::optional<double> optional_number(const nlohmann::json& request, std::string_view field,
                                      double low = -Limits::kLargestValue,
                                      double high = Limits::kLargestValue);
// The field as a whole number in [low, high].
int integer_field(const nlohmann::json& request, std::string_view field, int low, int high);
// The field as a string of at most Limits::kLongestText characters.
std::string string_field(const nlohmann::json& request, std::string_view field);
std::optional<std::string> optional_string(const nlohmann::json& request, std::string_view field);
// The field as true or false; false when it is missing (400 when it is not a boolean).
bool optional_flag(const nlohmann::json& request, std::string_view field);

// The field as a list of points, each [x, z] (metres): 400 when it is not a list or a point is not
// two numbers; 422 naming the point (from 1) when a coordinate is beyond Limits::kLargestValue, and
// naming the count when there are fewer than `fewest` or more than `most`.
std::vector<path::GroundPoint> points_field(const nlohmann::json& request, std::string_view field,
                                            std::size_t fewest, std::size_t most);

// Whether `name` is a name the workspace reads or writes: 1 to 64 letters, digits, '-' or '_'.
bool is_plain_name(std::string_view name);

}  // namespace fuzzygait::studio::detail
