#include "api_docs.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <map>
#include <sstream>

#include "core/particle_fields.hpp"

namespace seismpm::lua {

namespace {

// "a|b" as "\"a\" | \"b\"" (a Choice) or as {"a", "b"} (the default of Names).
std::string quoted_choices(const char* list, const char* separator, const char* open, const char* close) {
  std::string out = open, item;
  bool first = true;
  for (const char* c = list;; ++c) {
    if (*c == '|' || *c == '\0') {
      out += (first ? "" : separator) + ("\"" + item + "\"");
      first = false;
      item.clear();
      if (*c == '\0') break;
    } else {
      item += *c;
    }
  }
  return out + close;
}

std::string with_unit(std::string text, const Key& k) { return *k.unit ? text + " (" + k.unit + ")" : text; }

// What the value is: "number > 0 (m)", "\"gimp\" | \"linear\"", "a material".
std::string type_text(const Key& k) {
  const std::string range = k.range_text ? k.range_text : k.range.text();
  const std::string ranged = range.empty() ? "" : " " + range;
  switch (k.type) {
    case Type::Number:
      return with_unit("number" + ranged, k);
    case Type::Integer:
      return with_unit("whole number" + ranged, k);
    case Type::String:
      return "string";
    case Type::Boolean:
      return "true | false";
    case Type::Choice:
      return quoted_choices(k.choices, " | ", "", "");
    case Type::Point:
      return with_unit("{x, y}", k);
    case Type::Names:
      return "list of names {\"a\", ...}";
    case Type::Table: {
      std::string s = "table {";
      for (std::size_t i = 0; i < k.keys.size(); ++i) s += std::string(i ? ", " : " ") + k.keys[i].name;
      return s + " }";
    }
    case Type::Object:
      return std::string("a ") + k.object;
    case Type::Function:
      return "function";
    case Type::Custom:
      return with_unit(k.type_text, k);
    case Type::Positional:
      return "entries 1..n";
  }
  return "";
}

// The default as Lua would write it, or "" when no value states it.
std::string default_value(const Key& k) {
  if (k.mandatory || k.shown_default) return "";
  if (k.has_number_default()) return number_text(k.number);
  if (k.has_point_default()) return "{" + number_text(k.point[0]) + ", " + number_text(k.point[1]) + "}";
  if (!k.text) return "";
  if (k.type == Type::Boolean) return k.text;
  if (k.type == Type::Names) return quoted_choices(k.text, ", ", "{", "}");
  return std::string("\"") + k.text + "\"";
}

std::string default_text(const Key& k) {
  if (k.type == Type::Positional) return "";
  if (k.mandatory) return "required";
  if (k.shown_default) return k.shown_default;
  const std::string v = default_value(k);
  return v.empty() ? "optional" : v;
}

// The rows of a key and of a nested table's keys: {name, type, default, doc}.
void key_rows(const Key& k, const std::string& prefix, std::vector<std::array<std::string, 4>>& rows) {
  rows.push_back({prefix + k.name, type_text(k), default_text(k), k.doc});
  if (k.type == Type::Table)
    for (const Key& sub : k.keys) key_rows(sub, prefix + k.name + ".", rows);
}

std::vector<std::array<std::string, 4>> rows_of(const Function& f) {
  std::vector<std::array<std::string, 4>> rows;
  for (const Key& k : f.keys) key_rows(k, "", rows);
  return rows;
}

// A Markdown table cell: its | escaped.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

// How a script calls it: "mpm.model", or "m:run" for the method run of a model.
std::string call_of(const Function& f) {
  if (f.call) return f.call;
  const std::string name = f.name;
  const auto colon = name.find(':');
  if (colon == std::string::npos) return name;
  static const std::map<std::string, std::string> kReceivers = {{"model", "m"},   {"body", "b"},  {"probe", "p"},
                                                                {"history", "h"}, {"shape", "s"}, {"material", "mat"}};
  const auto it = kReceivers.find(name.substr(0, colon));
  return (it == kReceivers.end() ? name.substr(0, colon) : it->second) + name.substr(colon);
}

}  // namespace

const std::vector<ApiSection>& api_sections() {
  static const std::vector<ApiSection> sections = {
      {"Models", model_functions()},
      {"Building a model: bodies, contact, fixities, probes", model_building_functions()},
      {"Runs and phases: initial stresses and shaking", phase_functions()},
      {"Output: ParaView files, probe histories, plots", output_functions()},
      {"Checkpoints and restarts", checkpoint_functions()},
      {"Bodies", body_functions()},
      {"Probes", probe_functions()},
      {"Materials", material_functions()},
      {"Shapes", shape_functions()},
      {"Histories", history_functions()},
      {"Simple methods beside MPM: Newmark's sliding block", methods_functions()},
      {"Plots", plot_functions()},
      {"Limit equilibrium", lem_functions()},
      {"Strength reduction", strength_reduction_functions()},
      {"Scenario parameters and the session", session_functions()},
      {"Geometry (Lua library, lua/seismpm.lua)", library_functions()},
      {"Console", help_functions()},
  };
  return sections;
}

const std::vector<const Function*>& api_functions() {
  static const std::vector<const Function*> all = [] {
    std::vector<const Function*> v;
    for (const auto& s : api_sections())
      for (const Function& f : s.functions) v.push_back(&f);
    return v;
  }();
  return all;
}

const Function* find_function(const std::string& name) {
  for (const Function* f : api_functions())
    if (name == f->name) return f;
  return nullptr;
}

std::string signature(const Function& f) {
  if (f.keys.empty()) return call_of(f);
  std::string s = call_of(f) + "{";
  for (std::size_t i = 0; i < f.keys.size(); ++i) {
    const Key& k = f.keys[i];
    const std::string v = default_value(k);
    s += std::string(i ? ", " : " ") + k.name + (v.empty() ? "" : " = " + v);
  }
  return s + " }";
}

std::string help_text(const Function& f) {
  std::ostringstream os;
  os << signature(f) << "\n  " << f.summary << "\n";
  const auto rows = rows_of(f);
  std::size_t width = 0;
  for (const auto& r : rows) width = std::max(width, r[0].size());
  for (const auto& r : rows) {
    os << "  " << r[0] << std::string(width + 2 - r[0].size(), ' ') << r[1];
    if (!r[2].empty()) os << (r[2] == "required" ? ", required" : ", default " + r[2]);
    os << ": " << r[3] << "\n";
  }
  os << "  example: " << f.example << "\n";
  return os.str();
}

std::string summary_line(const Function& f) {
  constexpr std::size_t kWidth = 100;
  const std::string text = f.summary;
  std::size_t end = text.size(), depth = 0, soft = std::string::npos;  // soft: a ": " or "; " to cut at
  for (std::size_t i = 0; i + 1 < text.size(); ++i) {
    const char c = text[i];
    if (c == '(' || c == '{') ++depth;
    if ((c == ')' || c == '}') && depth > 0) --depth;
    if (depth == 0 && text[i + 1] == ' ' && c == '.') {
      end = i + 1;
      break;
    }
    // Not before the middle: "A control point: follows ..." says more with the words after the colon.
    if (depth == 0 && text[i + 1] == ' ' && (c == ':' || c == ';') && i >= kWidth / 2 && i < kWidth &&
        soft == std::string::npos)
      soft = i;
  }
  if (end <= kWidth) return text.substr(0, end);
  if (soft != std::string::npos) return text.substr(0, soft);
  const std::size_t space = text.rfind(' ', kWidth - 3);
  return text.substr(0, space == std::string::npos ? kWidth - 3 : space) + "...";
}

std::string listing(const std::vector<const Function*>& functions) {
  std::size_t width = 0;
  for (const Function* f : functions) width = std::max(width, std::string(f->name).size());
  std::string out;
  for (const Function* f : functions)
    out += "  " + std::string(f->name) + std::string(width + 2 - std::string(f->name).size(), ' ') + summary_line(*f) +
           "\n";
  return out;
}

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool key_matches(const Key& k, const std::string& query) {
  if (lower(k.name).find(query) != std::string::npos || lower(k.doc).find(query) != std::string::npos) return true;
  if (k.type == Type::Table)
    for (const Key& sub : k.keys)
      if (key_matches(sub, query)) return true;
  return false;
}

}  // namespace

std::vector<const Function*> search(const std::string& query) {
  const std::string q = lower(query);
  std::vector<const Function*> found;
  if (q.find_first_not_of(" \t") == std::string::npos) return found;
  for (const Function* f : api_functions()) {
    bool hit = lower(f->name).find(q) != std::string::npos || lower(f->summary).find(q) != std::string::npos ||
               (f->call && lower(f->call).find(q) != std::string::npos);
    for (const Key& k : f->keys) hit = hit || key_matches(k, q);
    if (hit) found.push_back(f);
  }
  return found;
}

std::string search_text(const std::string& query) {
  const auto found = search(query);
  if (found.empty())
    return "nothing in the API matches '" + query +
           "' (names, descriptions and keys were searched); help() lists "
           "everything\n";
  return std::to_string(found.size()) + (found.size() == 1 ? " entry matches '" : " entries match '") + query +
         "' (help(\"name\") shows one in full):\n" + listing(found);
}

namespace {

// The particle fields that b:field, probe:get, probes.csv and the .vtu files share, from their table.
std::string particle_fields_markdown() {
  std::ostringstream os;
  os << "\n## Particle fields\n\n"
     << "The names `b:field`, `probe:get` and `probe:series` take, and the columns of `probes.csv` "
        "(`<probe>.<name>`),\n"
     << "with the `.vtu` array (and component) each is written in.\n\n"
     << "| field | `.vtu` array | unit | meaning |\n|---|---|---|---|\n";
  for (const Field f : particle_fields(3)) {
    const FieldInfo& fi = field_info(f);
    const QuantityInfo& q = quantity_info(fi.quantity);
    os << "| `" << fi.name << "` | ";
    if (!q.vtu_array)
      os << "the points";
    else
      os << "`" << q.name << "`";
    if (q.components > 1) os << " [" << fi.component << "]";
    os << " | " << q.unit << " | " << q.meaning << (fi.min_dim == 3 ? " (3D models)" : "") << " |\n";
  }
  return os.str();
}

}  // namespace

std::string api_markdown() {
  std::ostringstream os;
  os << "# Lua API reference\n\n"
     << "Generated from the key tables of the bindings, the same ones that check every call and that `help()`\n"
     << "shows in the console (`seismpm --api-doc`). Every function that takes a table of named arguments checks\n"
     << "it: an unknown key, a missing required key, a wrong type or a value out of range raises an error naming\n"
     << "the key and the allowed range. SI units (m, kg, s, Pa); angles in degrees.\n";
  for (const auto& section : api_sections()) {
    os << "\n## " << section.title << "\n";
    for (const Function& f : section.functions) {
      os << "\n### `" << signature(f) << "`\n\n" << f.summary << "\n";
      const auto rows = rows_of(f);
      if (!rows.empty()) {
        os << "\n| key | value | default | meaning |\n|---|---|---|---|\n";
        for (const auto& r : rows)
          os << "| `" << r[0] << "` | " << cell(r[1]) << " | " << cell(r[2]) << " | " << cell(r[3]) << " |\n";
      }
      os << "\n```lua\n" << f.example << "\n```\n";
    }
  }
  os << particle_fields_markdown();
  return os.str();
}

}  // namespace seismpm::lua
