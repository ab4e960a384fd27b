// JSON at the file boundary, through nlohmann-json (docs/DEPENDENCIES.md): the typed results of
// metrics.h and solver.h are turned into JSON here and nowhere earlier, and the JSON files the
// project reads (its own summary.json, the reference set's summary.json and metrics.json) are
// parsed here. Internal to the repository: no public header includes nlohmann-json.
#ifndef DYNSLAM_SRC_JSON_IO_H_
#define DYNSLAM_SRC_JSON_IO_H_

#include <initializer_list>
#include <string>

#include <nlohmann/json.hpp>

#include "dynslam/metrics.h"
#include "dynslam/status.h"

namespace dynslam {

// Objects keep insertion order, so written files are stable. Integers stay integers (vertex ids
// up to 2^63 exactly); doubles are written in the shortest form that reads back bit-exactly,
// independent of the C locale.
using JsonValue = nlohmann::ordered_json;

// The shape of the reference metrics.json (SPEC §5).
JsonValue MetricsToJson(const Metrics& metrics);

// Indented by two spaces, no trailing newline; non-finite numbers as null (JSON has no NaN),
// strings as UTF-8 (invalid bytes become U+FFFD rather than an exception).
std::string DumpJson(const JsonValue& json);

// Errors name `name` (or the file) and the line; NaN, Infinity and trailing commas are errors.
Expected<JsonValue> ParseJson(const std::string& text, const std::string& name);
Expected<JsonValue> ReadJsonFile(const std::string& path);

// The number at a path of object keys, or NaN when a key is missing or the value not a number.
double NumberAt(const JsonValue& json, std::initializer_list<const char*> path);

}  // namespace dynslam

#endif  // DYNSLAM_SRC_JSON_IO_H_
