#include "scenes/load_scene.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <unordered_map>

#include <toml++/toml.h>

#include "scenes/enum_names.hpp"
#include "scenes/frame_mechanisms.hpp"
#include "scenes/message_text.hpp"
#include "scenes/scene_text.hpp"
#include "scenes/toml_guard.hpp"
#include "scenes/units.hpp"
#include "scenes/validate_scene.hpp"

namespace fetic::scenes {
namespace {

constexpr long long kMaxElements = 10'000'000;
constexpr long long kMaxSubdomains = 1'000'000;

const std::vector<std::string> kTopKeys = {"title", "model",   "defaults", "strut",
                                           "load",  "contact", "units",    "joint"};
const std::vector<std::string> kStrutKeys = {"name",
                                             "from",
                                             "to",
                                             "E",
                                             "area",
                                             "elements",
                                             "subdomains",
                                             "fixed",
                                             "height",
                                             "thickness",
                                             "nu",
                                             "elements_across",
                                             "subdomains_across",
                                             "inertia",
                                             "pinned"};
const std::vector<std::string> kLoadKeys = {"strut", "at", "force", "per_length", "moment"};
const std::vector<std::string> kContactKeys = {"a", "b", "normal"};
const std::vector<std::string> kJointKeys = {"ends", "kind"};

int line_of(const toml::node& node) {
  return static_cast<int>(node.source().begin.line);
}
int line_of(const toml::key& key) {
  return static_cast<int>(key.source().begin.line);
}

// What a value is, in the words of a message ("must be a number, got a string").
constexpr EnumName<toml::node_type> kTomlTypeNames[] = {
    {toml::node_type::none, "nothing"},       {toml::node_type::table, "a table"},
    {toml::node_type::array, "an array"},     {toml::node_type::string, "a string"},
    {toml::node_type::integer, "an integer"}, {toml::node_type::floating_point, "a number"},
    {toml::node_type::boolean, "a boolean"},  {toml::node_type::date, "a date"},
    {toml::node_type::time, "a time"},        {toml::node_type::date_time, "a date-time"}};

std::string type_name(const toml::node& node) {
  return name_of(kTomlTypeNames, node.type());
}

// " (did you mean 'area'?)" when a known key is close to the unknown one.
std::string suggestion(std::string_view key, const std::vector<std::string>& known) {
  std::string best;
  size_t best_distance = 3;
  for (const std::string& candidate : known) {
    const size_t d = edit_distance(key, candidate, LetterCase::Ignored);
    if (d < best_distance) {
      best_distance = d;
      best = candidate;
    }
  }
  return best.empty() ? "" : " (did you mean " + quoted(best) + "?)";
}

bool valid_name(std::string_view name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
}

// Puts a value read (below) into its field; false when there was none to read, the reader
// having said why. `ok = assign(...) && ok` reads every key even after a problem, so that
// one pass reports them all.
template <class T, class Field>
bool assign(const std::optional<T>& value, Field& field) {
  if (value) field = *value;
  return value.has_value();
}

// Reads typed values out of TOML tables and records every problem it meets.
class Reader {
 public:
  explicit Reader(std::vector<Problem>& problems) : problems_(problems) {}

  void error(int line, std::string message) { problems_.push_back({line, std::move(message)}); }

  void check_keys(const toml::table& table, const std::vector<std::string>& known,
                  const std::string& where) {
    for (auto&& [key, node] : table) {
      if (std::find(known.begin(), known.end(), key.str()) == known.end())
        error(line_of(key),
              "unknown key " + quoted(key.str()) + " in " + where + suggestion(key.str(), known));
    }
  }

  std::optional<double> number(const toml::node& node, const std::string& what) {
    if (auto v = node.as_floating_point()) {
      const double value = v->get();
      if (!std::isfinite(value)) {
        error(line_of(node), what + " must be a finite number, got " + number_text(value));
        return std::nullopt;
      }
      return value;
    }
    if (auto v = node.as_integer()) return static_cast<double>(v->get());
    error(line_of(node), what + " must be a number, got " + type_name(node));
    return std::nullopt;
  }

  std::optional<double> positive(const toml::node& node, const std::string& what) {
    auto value = number(node, what);
    if (value && !(*value > 0.0)) {
      error(line_of(node), what + " must be greater than 0, got " + number_text(*value));
      return std::nullopt;
    }
    return value;
  }

  std::optional<long long> integer(const toml::node& node, const std::string& what, long long low,
                                   long long high) {
    auto v = node.as_integer();
    if (!v) {
      error(line_of(node), what + " must be an integer, got " + type_name(node));
      return std::nullopt;
    }
    const long long value = v->get();
    if (value < low || value > high) {
      error(line_of(node), what + " must be between " + std::to_string(low) + " and " +
                               std::to_string(high) + ", got " + std::to_string(value));
      return std::nullopt;
    }
    return value;
  }

  std::optional<std::string> string(const toml::node& node, const std::string& what) {
    if (auto v = node.as_string()) return v->get();
    error(line_of(node), what + " must be a string, got " + type_name(node));
    return std::nullopt;
  }

  std::optional<Point> point(const toml::node& node, const std::string& what) {
    const toml::array* array = node.as_array();
    if (!array || array->size() != 2) {
      error(line_of(node), what + " must be an array of two numbers [x, y], got " +
                               (array ? "an array of " + std::to_string(array->size()) + " values"
                                      : type_name(node)));
      return std::nullopt;
    }
    auto x = number(*array->get(0), what + "[0]");
    auto y = number(*array->get(1), what + "[1]");
    if (!x || !y) return std::nullopt;
    return Point{*x, *y};
  }

  std::optional<StrutEnd> end(const toml::node& node, const std::string& what) {
    auto text = string(node, what);
    if (!text) return std::nullopt;
    if (*text == "from") return StrutEnd::From;
    if (*text == "to") return StrutEnd::To;
    error(line_of(node), what + " must be \"from\" or \"to\", got \"" + *text + "\"");
    return std::nullopt;
  }

 private:
  std::vector<Problem>& problems_;
};

// A strut key looked up in the strut's own table, then in [defaults].
class StrutKeys {
 public:
  StrutKeys(const toml::table& own, const toml::table* defaults) : own_(own), defaults_(defaults) {}
  const toml::node* find(std::string_view key) const {
    if (const toml::node* node = own_.get(key)) return node;
    return defaults_ ? defaults_->get(key) : nullptr;
  }

 private:
  const toml::table& own_;
  const toml::table* defaults_;
};

class SceneParser {
 public:
  SceneParser(Scene& scene, std::vector<Problem>& problems) : scene_(scene), read_(problems) {}

  void parse(const toml::table& root) {
    read_.check_keys(root, kTopKeys, "the scene (top level)");
    parse_header(root);
    parse_units(root);
    const toml::table* defaults = parse_defaults(root);
    parse_struts(root, defaults);
    parse_loads(root);
    parse_contacts(root);
    parse_joints(root);
  }

 private:
  void parse_header(const toml::table& root) {
    if (const toml::node* title = root.get("title")) {
      if (auto text = read_.string(*title, "'title'")) scene_.title = *text;
    }
    const toml::node* model = root.get("model");
    if (!model) {
      read_.error(0, "missing key 'model' (\"bar\", \"plane\" or \"frame\")");
      return;
    }
    if (auto text = read_.string(*model, "'model'")) {
      if (const auto kind = parse_model(*text)) {
        scene_.model = *kind;
      } else {
        read_.error(line_of(*model),
                    "'model' must be \"bar\", \"plane\" or \"frame\", got \"" + *text + "\"");
      }
    }
  }

  // [units]: length and force, each optional (SI by default); names from scenes/units.hpp.
  void parse_units(const toml::table& root) {
    const toml::node* node = root.get("units");
    if (!node) return;
    const toml::table* units = node->as_table();
    if (!units) {
      read_.error(line_of(*node), "'units' must be a table [units], got " + type_name(*node));
      return;
    }
    read_.check_keys(*units, {"length", "force"}, "[units]");
    const auto unit = [&](const char* key, const std::vector<std::string>& names,
                          std::string& out) {
      const toml::node* value = units->get(key);
      if (!value) return;
      const auto text = read_.string(*value, std::string("'units.") + key + "'");
      if (!text) return;
      if (std::find(names.begin(), names.end(), *text) == names.end()) {
        std::string list;
        for (const std::string& name : names)
          list += (list.empty() ? "" : ", ") + name;
        read_.error(line_of(*value), std::string("'units.") + key + "' must be one of " + list +
                                         ", got \"" + *text + "\"");
        return;
      }
      out = *text;
    };
    unit("length", length_unit_names(), scene_.units.length);
    unit("force", force_unit_names(), scene_.units.force);
  }

  const toml::table* parse_defaults(const toml::table& root) {
    const toml::node* node = root.get("defaults");
    if (!node) return nullptr;
    const toml::table* defaults = node->as_table();
    if (!defaults) {
      read_.error(line_of(*node), "'defaults' must be a table [defaults], got " + type_name(*node));
      return nullptr;
    }
    read_.check_keys(*defaults, kStrutKeys, "[defaults]");
    return defaults;
  }

  // The array of tables under `key`, or nullptr after reporting what is wrong.
  const toml::array* table_array(const toml::table& root, std::string_view key) {
    const toml::node* node = root.get(key);
    if (!node) return nullptr;
    const toml::array* array = node->as_array();
    if (!array || !array->is_array_of_tables()) {
      read_.error(line_of(*node), quoted(key) + " must be an array of tables [[" +
                                      std::string(key) + "]], got " + type_name(*node));
      return nullptr;
    }
    return array;
  }

  // Every table of an array [[key]], in order: its keys checked against `known`, then read
  // by `parse_one` into an entry that keeps the table's line; the entry joins `out` when
  // parse_one found it whole. The label names the entry in messages ("load #2").
  template <class Entry>
  void parse_each(const toml::array& tables, const std::string& key,
                  const std::vector<std::string>& known,
                  bool (SceneParser::*parse_one)(const toml::table&, const std::string&, Entry&),
                  std::vector<Entry>& out) {
    for (size_t i = 0; i < tables.size(); ++i) {
      const toml::table& table = *tables.get(i)->as_table();
      read_.check_keys(table, known, "[[" + key + "]]");
      Entry entry;
      entry.line = line_of(table);
      if ((this->*parse_one)(table, key + " #" + std::to_string(i + 1), entry))
        out.push_back(std::move(entry));
    }
  }

  void parse_struts(const toml::table& root, const toml::table* defaults) {
    const toml::array* struts = table_array(root, "strut");
    if (!struts) {
      if (!root.get("strut")) read_.error(0, "the scene has no [[strut]]");
      return;
    }
    for (size_t i = 0; i < struts->size(); ++i) {
      const toml::table& table = *struts->get(i)->as_table();
      Strut strut = parse_strut(table, defaults, static_cast<int>(i));
      if (!strut.name.empty()) {
        auto [it, inserted] = strut_index_.emplace(strut.name, static_cast<int>(i));
        if (!inserted)
          read_.error(strut.line, "duplicate strut name " + quoted(strut.name) +
                                      " (first defined on line " +
                                      std::to_string(scene_.struts[it->second].line) + ")");
      }
      scene_.struts.push_back(std::move(strut));
    }
  }

  Strut parse_strut(const toml::table& table, const toml::table* defaults, int index) {
    read_.check_keys(table, kStrutKeys, "[[strut]]");
    const StrutKeys keys(table, defaults);
    Strut strut;
    strut.line = line_of(table);
    std::string label = "strut #" + std::to_string(index + 1);
    if (const toml::node* name = keys.find("name")) {
      if (auto text = read_.string(*name, "strut 'name'")) {
        if (valid_name(*text)) {
          strut.name = *text;
          label = "strut " + quoted(*text);
        } else {
          read_.error(line_of(*name), "strut name \"" + *text +
                                          "\" must be non-empty and use only letters, digits, "
                                          "'_' and '-'");
        }
      }
    } else {
      read_.error(strut.line, label + ": missing key 'name'");
    }
    auto required = [&](std::string_view key) -> const toml::node* {
      const toml::node* node = keys.find(key);
      if (!node) read_.error(strut.line, label + ": missing key " + quoted(key));
      return node;
    };
    auto what = [&](std::string_view key) { return label + ": " + quoted(key); };

    if (auto node = required("from"))
      if (auto p = read_.point(*node, what("from"))) strut.from = *p;
    if (auto node = required("to"))
      if (auto p = read_.point(*node, what("to"))) strut.to = *p;
    if (auto node = required("E"))
      if (auto v = read_.positive(*node, what("E"))) strut.E = *v;
    parse_division(keys, required, what, "elements", "subdomains", strut.elements,
                   strut.subdomains);
    if (auto node = keys.find("fixed")) parse_fixed(*node, what("fixed"), strut);

    if (scene_.model == ModelKind::Plane) {
      parse_plane_keys(keys, strut, label, required, what);
    } else {
      if (auto node = required("area"))
        if (auto v = read_.positive(*node, what("area"))) strut.area = *v;
    }
    if (scene_.model == ModelKind::Frame) {
      parse_frame_strut_keys(keys, strut, required, what);
    } else if (const toml::node* pinned = table.get("pinned")) {
      read_.error(line_of(*pinned), what("pinned") +
                                        ": pinned supports exist in the frame model only "
                                        "(model = \"frame\"); use 'fixed'");
    }
    return strut;
  }

  template <class Required, class What>
  void parse_plane_keys(const StrutKeys& keys, Strut& strut, const std::string& label,
                        Required required, What what) {
    (void)label;
    if (auto node = required("height"))
      if (auto v = read_.positive(*node, what("height"))) strut.height = *v;
    if (auto node = required("thickness"))
      if (auto v = read_.positive(*node, what("thickness"))) strut.thickness = *v;
    if (auto node = required("nu")) {
      if (auto v = read_.number(*node, what("nu"))) {
        if (*v > -1.0 && *v < 0.5)
          strut.nu = *v;
        else
          read_.error(line_of(*node), what("nu") +
                                          " (Poisson's ratio) must lie strictly between -1 and "
                                          "0.5, got " +
                                          number_text(*v));
      }
    }
    parse_division(keys, required, what, "elements_across", "subdomains_across",
                   strut.elements_across, strut.subdomains_across);
  }

  // A count of elements (required) and of the subdomains they are cut into (optional), at
  // most one subdomain per element: along a strut, or across a plane strut.
  template <class Required, class What>
  void parse_division(const StrutKeys& keys, Required required, What what,
                      const std::string& elements_key, const std::string& subdomains_key,
                      int& elements, int& subdomains) {
    if (auto node = required(elements_key))
      if (auto v = read_.integer(*node, what(elements_key), 1, kMaxElements))
        elements = static_cast<int>(*v);
    const toml::node* node = keys.find(subdomains_key);
    if (!node) return;
    const auto v = read_.integer(*node, what(subdomains_key), 1, kMaxSubdomains);
    if (!v) return;
    subdomains = static_cast<int>(*v);
    if (elements > 0 && subdomains > elements)
      read_.error(line_of(*node), what(subdomains_key) + " must be between 1 and " + elements_key +
                                      " (" + std::to_string(elements) + "), got " +
                                      std::to_string(subdomains));
  }

  void parse_fixed(const toml::node& node, const std::string& what, Strut& strut) {
    parse_end_flags(node, what, strut.fixed_from, strut.fixed_to);
  }

  // A list of strut ends: [], ["from"], ["to"] or ["from", "to"].
  void parse_end_flags(const toml::node& node, const std::string& what, bool& from, bool& to) {
    const toml::array* array = node.as_array();
    if (!array) {
      read_.error(line_of(node), what +
                                     " must be an array: [], [\"from\"], [\"to\"] or "
                                     "[\"from\", \"to\"], got " +
                                     type_name(node));
      return;
    }
    for (const toml::node& item : *array) {
      auto end = read_.end(item, what + " entry");
      if (!end) continue;
      bool& flag = *end == StrutEnd::From ? from : to;
      if (flag) read_.error(line_of(item), what + " lists \"" + to_string(*end) + "\" twice");
      flag = true;
    }
  }

  // Resolved after all struts are read, so loads and contacts may come first in the file.
  // A hash lookup: a scene of 100,000 loads must not search 200,000 struts for each.
  int find_strut(const std::string& name) const {
    const auto it = strut_index_.find(name);
    return it == strut_index_.end() ? -1 : it->second;
  }

  std::optional<int> strut_reference(const toml::node& node, const std::string& what) {
    auto name = read_.string(node, what);
    if (!name) return std::nullopt;
    const int index = find_strut(*name);
    if (index < 0) {
      read_.error(line_of(node), what + " names an unknown strut " + quoted(*name));
      return std::nullopt;
    }
    return index;
  }

  void parse_loads(const toml::table& root) {
    if (const toml::array* loads = table_array(root, "load"))
      parse_each(*loads, "load", kLoadKeys, &SceneParser::parse_load, scene_.loads);
  }

  // One [[load]]: the strut, then the force by model (frame loads below).
  bool parse_load(const toml::table& table, const std::string& label, Load& load) {
    bool ok = true;
    if (const toml::node* node = table.get("strut")) {
      ok = assign(strut_reference(*node, label + ": 'strut'"), load.strut) && ok;
    } else {
      read_.error(load.line, label + ": missing key 'strut'");
      ok = false;
    }
    const toml::node* at = table.get("at");
    const toml::node* force = table.get("force");
    const toml::node* per_length = table.get("per_length");
    if (scene_.model == ModelKind::Frame) {
      const bool parsed = parse_frame_load(table, label, load);
      return ok && parsed;
    }
    if (const toml::node* moment = table.get("moment")) {
      read_.error(line_of(*moment), label + ": 'moment' needs the frame model (model = \"frame\")");
      ok = false;
    }
    if (per_length && (at || force)) {
      read_.error(load.line, label +
                                 ": give either 'at' and 'force' (a force at a strut end) "
                                 "or 'per_length' (a force per unit length), not both");
      ok = false;
    } else if (per_length) {
      load.per_length = true;
      ok = assign(read_.point(*per_length, label + ": 'per_length'"), load.force) && ok;
    } else if (at || force) {
      if (!at) read_.error(load.line, label + ": missing key 'at' (\"from\" or \"to\")");
      if (!force) read_.error(load.line, label + ": missing key 'force' ([fx, fy] in N)");
      ok = ok && at && force;
      if (at) ok = assign(read_.end(*at, label + ": 'at'"), load.at) && ok;
      if (force) ok = assign(read_.point(*force, label + ": 'force'"), load.force) && ok;
    } else {
      read_.error(load.line, label +
                                 ": missing the force: give 'at' and 'force', or "
                                 "'per_length'");
      ok = false;
    }
    return ok;
  }

  std::optional<EndRef> end_reference(const toml::node& node, const std::string& what) {
    auto text = read_.string(node, what);
    if (!text) return std::nullopt;
    if (scene_.model == ModelKind::Frame) return frame_node_reference(node, *text, what);
    const size_t dot = text->rfind('.');
    const std::string name = dot == std::string::npos ? *text : text->substr(0, dot);
    const std::string end = dot == std::string::npos ? "" : text->substr(dot + 1);
    if (end != "from" && end != "to") {
      read_.error(line_of(node), what +
                                     " must name a strut end as \"NAME.from\" or "
                                     "\"NAME.to\", got \"" +
                                     *text + "\"");
      return std::nullopt;
    }
    const int index = find_strut(name);
    if (index < 0) {
      read_.error(line_of(node), what + " names an unknown strut " + quoted(name));
      return std::nullopt;
    }
    return EndRef{index, end == "from" ? StrutEnd::From : StrutEnd::To};
  }

  void parse_contacts(const toml::table& root) {
    if (const toml::array* contacts = table_array(root, "contact"))
      parse_each(*contacts, "contact", kContactKeys, &SceneParser::parse_contact, scene_.contacts);
  }

  // One [[contact]]: the two strut ends (nodes in the frame model) and a given normal.
  bool parse_contact(const toml::table& table, const std::string& label, Contact& contact) {
    std::optional<EndRef> a, b;
    if (const toml::node* node = table.get("a"))
      a = end_reference(*node, label + ": 'a'");
    else
      read_.error(contact.line, label + ": missing key 'a'");
    if (const toml::node* node = table.get("b"))
      b = end_reference(*node, label + ": 'b'");
    else
      read_.error(contact.line, label + ": missing key 'b'");
    if (const toml::node* normal = table.get("normal")) {
      if (scene_.model != ModelKind::Frame) {
        read_.error(line_of(*normal), label +
                                          ": 'normal' needs the frame model (model = "
                                          "\"frame\"); here the normal follows a's axis");
        return false;
      }
      if (!parse_contact_normal(*normal, label, contact)) return false;
    }
    if (!a || !b) return false;
    contact.a = *a;
    contact.b = *b;
    return true;
  }

  // ---- Frame model (SCENES.md "Frame model"): its keys, kept apart from the others ----

  template <class Required, class What>
  void parse_frame_strut_keys(const StrutKeys& keys, Strut& strut, Required required, What what) {
    if (auto node = required("inertia"))
      if (auto v = read_.positive(*node, what("inertia"))) strut.inertia = *v;
    if (auto node = keys.find("pinned")) {
      parse_end_flags(*node, what("pinned"), strut.pinned_from, strut.pinned_to);
      for (StrutEnd end : {StrutEnd::From, StrutEnd::To})
        if (strut.fixed(end) && strut.pinned(end))
          read_.error(line_of(*node), what("pinned") + ": the end \"" + to_string(end) +
                                          "\" is already clamped ('fixed'); an end is either "
                                          "clamped or pinned");
    }
  }

  // 'at' of a frame load: "from", "to", or a node index (an integer, or its digits as a
  // string); the range is checked once the strut is known.
  std::optional<int> frame_node_index(const toml::node& node, const std::string& what,
                                      const Strut* strut) {
    long long index = -1;
    if (auto v = node.as_integer()) {
      index = v->get();
    } else if (auto t = node.as_string()) {
      const std::string& text = t->get();
      if (text == "from") return 0;
      if (text == "to") return strut ? strut->elements : 0;
      if (text.empty() || text.size() > 18 ||
          !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        read_.error(line_of(node),
                    what + " must be \"from\", \"to\" or a node index, got \"" + text + "\"");
        return std::nullopt;
      }
      index = std::stoll(text);
    } else {
      read_.error(line_of(node),
                  what + " must be \"from\", \"to\" or a node index, got " + type_name(node));
      return std::nullopt;
    }
    if (strut && strut->elements > 0 && (index < 0 || index > strut->elements)) {
      read_.error(line_of(node), what + ": node index " + std::to_string(index) +
                                     " is out of range: strut " + quoted(strut->name) +
                                     " has nodes 0.." + std::to_string(strut->elements));
      return std::nullopt;
    }
    return static_cast<int>(index);
  }

  // A frame load: 'at' with 'force' and/or 'moment', or 'per_length'.
  bool parse_frame_load(const toml::table& table, const std::string& label, Load& load) {
    const toml::node* at = table.get("at");
    const toml::node* force = table.get("force");
    const toml::node* moment = table.get("moment");
    const toml::node* per_length = table.get("per_length");
    const Strut* strut = load.strut >= 0 ? &scene_.struts[load.strut] : nullptr;
    if (per_length && (at || force || moment)) {
      read_.error(load.line, label +
                                 ": give either 'at' with 'force' and/or 'moment' (at a node) "
                                 "or 'per_length' (a force per unit length), not both");
      return false;
    }
    if (per_length) {
      load.per_length = true;
      return assign(read_.point(*per_length, label + ": 'per_length'"), load.force);
    }
    if (!at && !force && !moment) {
      read_.error(load.line, label +
                                 ": missing the load: give 'at' with 'force' and/or 'moment', "
                                 "or 'per_length'");
      return false;
    }
    bool ok = true;
    if (!at) {
      read_.error(load.line, label + ": missing key 'at' (\"from\", \"to\" or a node index)");
      ok = false;
    }
    if (!force && !moment) {
      read_.error(load.line, label + ": missing key 'force' ([fx, fy] in N) or 'moment' (N m)");
      ok = false;
    }
    if (at) {
      auto index = frame_node_index(*at, label + ": 'at'", strut);
      ok = ok && index.has_value();
      if (index && strut) {
        const auto* text = at->as_string();
        if (text && text->get() == "from") {
          load.at = StrutEnd::From;
        } else if (text && text->get() == "to") {
          load.at = StrutEnd::To;
        } else {
          load.node = *index;
        }
      }
    }
    if (force) ok = assign(read_.point(*force, label + ": 'force'"), load.force) && ok;
    if (moment) ok = assign(read_.number(*moment, label + ": 'moment'"), load.moment) && ok;
    return ok;
  }

  // "NAME.from", "NAME.to" or "NAME@k".
  std::optional<EndRef> frame_node_reference(const toml::node& node, const std::string& text,
                                             const std::string& what) {
    const size_t at = text.rfind('@');
    const size_t dot = text.rfind('.');
    const bool indexed = at != std::string::npos && (dot == std::string::npos || dot < at);
    const std::string end = dot == std::string::npos ? "" : text.substr(dot + 1);
    if (!indexed && end != "from" && end != "to") {
      read_.error(line_of(node), what +
                                     " must name a strut node as \"NAME.from\", \"NAME.to\" "
                                     "or \"NAME@k\" (node k), got \"" +
                                     text + "\"");
      return std::nullopt;
    }
    const std::string name = text.substr(0, indexed ? at : dot);
    EndRef ref;
    ref.strut = find_strut(name);
    if (ref.strut < 0) {
      read_.error(line_of(node), what + " names an unknown strut " + quoted(name));
      return std::nullopt;
    }
    if (!indexed) {
      ref.end = end == "from" ? StrutEnd::From : StrutEnd::To;
      return ref;
    }
    const std::string digits = text.substr(at + 1);
    if (digits.empty() || digits.size() > 18 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      read_.error(line_of(node),
                  what + ": \"" + text + "\" must end in a node index, e.g. \"" + name + "@0\"");
      return std::nullopt;
    }
    const long long k = std::stoll(digits);
    const Strut& strut = scene_.struts[ref.strut];
    if (strut.elements > 0 && k > strut.elements) {
      read_.error(line_of(node), what + ": node index " + std::to_string(k) +
                                     " is out of range: strut " + quoted(name) + " has nodes 0.." +
                                     std::to_string(strut.elements));
      return std::nullopt;
    }
    ref.node = static_cast<int>(k);
    return ref;
  }

  bool parse_contact_normal(const toml::node& node, const std::string& label, Contact& contact) {
    auto n = read_.point(node, label + ": 'normal'");
    if (!n) return false;
    const double size = std::hypot((*n)[0], (*n)[1]);
    // A unit vector as people write it ([0.7071, 0.7071]) is accepted and normalized; a
    // vector of another length is more likely a mistake than a direction.
    if (!(std::abs(size - 1.0) <= kUnitTolerance)) {
      read_.error(line_of(node), label + ": 'normal' must be a unit vector, got length " +
                                     number_text(size) +
                                     (size > 0.0 ? " (divide it by its length)" : ""));
      return false;
    }
    contact.has_normal = true;
    contact.normal = *n;
    return true;
  }

  void parse_joints(const toml::table& root) {
    const toml::array* joints = table_array(root, "joint");
    if (!joints) return;
    if (scene_.model != ModelKind::Frame) {
      read_.error(line_of(*root.get("joint")),
                  "[[joint]] needs the frame model (model = \"frame\")");
      return;
    }
    parse_each(*joints, "joint", kJointKeys, &SceneParser::parse_joint, scene_.joints);
  }

  // One [[joint]]: its kind and the strut ends it connects.
  bool parse_joint(const toml::table& table, const std::string& label, Joint& joint) {
    bool ok = true;
    if (const toml::node* kind = table.get("kind")) {
      auto text = read_.string(*kind, label + ": 'kind'");
      if (text && *text == "rigid") {
        joint.kind = JointKind::Rigid;
      } else if (text && *text == "pinned") {
        joint.kind = JointKind::Pinned;
      } else {
        if (text)
          read_.error(line_of(*kind),
                      label + ": 'kind' must be \"rigid\" or \"pinned\", got \"" + *text + "\"");
        ok = false;
      }
    }
    const toml::node* ends = table.get("ends");
    if (!ends) {
      read_.error(joint.line, label + ": missing key 'ends' (two or more strut ends)");
      return false;
    }
    const toml::array* array = ends->as_array();
    if (!array || array->size() < 2) {
      read_.error(line_of(*ends), label + ": 'ends' must be an array of two or more strut ends " +
                                      "[\"A.to\", \"B.from\", ...], got " +
                                      (array ? "an array of " + std::to_string(array->size()) +
                                                   " value" + (array->size() == 1 ? "" : "s")
                                             : type_name(*ends)));
      return false;
    }
    for (const toml::node& item : *array) {
      auto text = read_.string(item, label + ": 'ends' entry");
      if (!text) {
        ok = false;
        continue;
      }
      auto ref = frame_node_reference(item, *text, label + ": 'ends' entry");
      if (!ref) {
        ok = false;
      } else if (ref->node >= 0) {
        read_.error(line_of(item), label +
                                       ": a joint connects strut ends (\"NAME.from\" or "
                                       "\"NAME.to\"), got \"" +
                                       *text + "\"");
        ok = false;
      } else {
        joint.ends.push_back(*ref);
      }
    }
    return ok;
  }

  // Accepted deviation of a given contact normal from unit length.
  static constexpr double kUnitTolerance = 1e-4;

  Scene& scene_;
  Reader read_;
  std::unordered_map<std::string, int> strut_index_;  // name -> first strut of that name
};

// parse_scene(), with `stop` asked between the steps of checks that take long on large
// scenes (the frame mechanism check): then a SceneError says the loading was interrupted.
Scene parse_scene_text(std::string_view text, const std::string& path,
                       const std::function<bool()>& stop) {
  if (Problem problem = toml_guard_problem(text); problem.line > 0)
    throw SceneError(path, {std::move(problem)});
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& error) {
    throw SceneError(path, {{static_cast<int>(error.source().begin.line),
                             "TOML syntax error: " + std::string(error.description())}});
  }
  Scene scene;
  scene.path = path;
  std::vector<Problem> problems;
  SceneParser(scene, problems).parse(root);
  try {
    if (problems.empty()) problems = validate_scene(scene, stop);
  } catch (const MechanismCheckStopped&) {
    throw SceneError(path, {{1, "interrupted while checking the scene"}});
  }
  if (!problems.empty()) throw SceneError(path, std::move(problems));
  return scene;
}

}  // namespace

Scene parse_scene(std::string_view text, const std::string& path) {
  return parse_scene_text(text, path, {});
}

Scene load_scene_file(const std::string& path, const std::function<bool()>& stop) {
  return parse_scene_text(read_scene_text(path, stop), path, stop);
}

}  // namespace fetic::scenes
