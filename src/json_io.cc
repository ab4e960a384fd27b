#include "src/json_io.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace dynslam {

JsonValue MetricsToJson(const Metrics& metrics) {
  auto family = [](const ObjectErrors& errors, const char* count_name) {
    JsonValue per_object = JsonValue::object();
    for (const auto& [object, mean] : errors.per_object) {
      per_object[std::to_string(object)] = {{count_name, mean.count},
                                            {"mean_rot_deg", mean.mean_rot_deg},
                                            {"mean_trans_m", mean.mean_trans_m}};
    }
    return JsonValue{{count_name, errors.count},
                     {"objects", errors.objects},
                     {"mean_rot_deg", errors.mean_rot_deg},
                     {"mean_trans_m", errors.mean_trans_m},
                     {"per_object", std::move(per_object)}};
  };
  JsonValue object_pose = family(metrics.object_pose, "pairs");
  // Only world-centric poses are composed from a ground-truth start (the reference files carry
  // the count for wc only).
  if (!metrics.object_centric) {
    object_pose["segments_without_ground_truth_start"] =
        metrics.segments_without_ground_truth_start;
  }
  return JsonValue{{"object_centric", metrics.object_centric},
                   {"camera",
                    {{"pairs", metrics.camera.count},
                     {"mean_rot_deg", metrics.camera.mean_rot_deg},
                     {"mean_trans_m", metrics.camera.mean_trans_m}}},
                   {"object_motion", family(metrics.object_motion, "motions")},
                   {"object_pose", std::move(object_pose)}};
}

std::string DumpJson(const JsonValue& json) {
  return json.dump(2, ' ', false, JsonValue::error_handler_t::replace);
}

Expected<JsonValue> ParseJson(const std::string& text, const std::string& name) {
  try {
    return JsonValue::parse(text);
  } catch (const JsonValue::parse_error& error) {
    // error.byte is 1-based and points just past the offending character.
    const size_t end = std::min(text.size(), error.byte == 0 ? 0 : error.byte - 1);
    const int64_t line = 1 + std::count(text.begin(), text.begin() + end, '\n');
    std::string message = error.what();
    const size_t detail = message.find("parse error");
    return Error{name, line,
                 "not valid JSON (" + message.substr(detail == std::string::npos ? 0 : detail) + ")"};
  } catch (const JsonValue::exception& error) {  // e.g. a number beyond a double's range
    return Error{name, 0, std::string("not valid JSON (") + error.what() + ")"};
  }
}

Expected<JsonValue> ReadJsonFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path, 0, "cannot open the file"};
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return ParseJson(buffer.str(), path);
}

double NumberAt(const JsonValue& json, std::initializer_list<const char*> path) {
  const JsonValue* node = &json;
  for (const char* key : path) {
    if (!node->is_object()) return std::nan("");
    const auto it = node->find(key);
    if (it == node->end()) return std::nan("");
    node = &*it;
  }
  return node->is_number() ? node->get<double>() : std::nan("");
}

}  // namespace dynslam
