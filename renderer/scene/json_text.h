// JSON values and parse errors as message text, shared by the readers of
// scene files (scene_json.cpp) and glTF files (gltf.cpp), so that both quote
// the user's input the same way.
#pragma once

#include <string>

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
