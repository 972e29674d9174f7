// JSON values and parse errors as message text, shared by the readers of
// scene files (scene_json.cpp) and glTF files (gltf.cpp), so that both quote
// the user's input the same way.
#pragma once

#include <string>

#include "core/errors.h"

namespace octrace {

// The value as the user wrote it, shortened, for "got ..." in messages.
template <typename Json>
std::string describe_json(const Json& v) {
  const std::string text = v.dump();
  if (text.size() <= 40) return text;
  if (v.is_array()) return "an array of " + std::to_string(v.size()) + " elements";
  if (v.is_object()) return "an object";
  return text.substr(0, 37) + "...";
}

// How deep a JSON document may nest. nlohmann's parser takes any depth, but
// dump() (describe_json) and tinygltf's reader recurse once a level, so a
// document of many thousand levels would overflow the stack: the readers
// refuse it while parsing (json_depth_limit).
inline constexpr int kMaxJsonDepth = 512;

// Throws InputError "WHERE: nested deeper than 512 levels" past
// kMaxJsonDepth; `depth` as nlohmann's parser callbacks receive it. WHERE
// ends in ": " (or is empty).
inline void check_json_depth(int depth, const std::string& where) {
  if (depth > kMaxJsonDepth)
    throw InputError(where + "nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
}

// A parser callback for nlohmann's parse() that keeps every value and
// checks the depth (check_json_depth).
template <typename Json>
typename Json::parser_callback_t json_depth_limit(const std::string& where) {
  return [where](int depth, typename Json::parse_event_t, Json&) {
    check_json_depth(depth, where);
    return true;
  };
}

// "invalid JSON at line 3, column 5: syntax error ..." from the what() of
// nlohmann's parse_error ("[json.exception.parse_error.101] parse error at line 3, ...").
inline std::string invalid_json_message(const std::string& what) {
  const size_t at = what.find(" at line ");
  return "invalid JSON" + (at == std::string::npos ? ": " + what : what.substr(at));
}

// "materials[2].albedo": the path of a node in a tree of nodes that know
// their parent, their member key or element index (is_element, index).
template <typename Node>
std::string json_path(const Node& n) {
  if (!n.parent) return "";
  const std::string p = json_path(*n.parent);
  if (n.is_element) return p + "[" + std::to_string(n.index) + "]";
  return p.empty() ? std::string(n.key) : p + "." + std::string(n.key);
}

}  // namespace octrace
