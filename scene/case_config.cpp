#include "scene/case_config.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <system_error>
#include <tuple>
#include <type_traits>

#include "hydro/closure.hpp"
#include "md_bridge/particle_engine_registry.hpp"

namespace granvv::app {

namespace {

// ---------------------------------------------------------------------------------------------
// Small text helpers.
// ---------------------------------------------------------------------------------------------

// Messages are one line: escape what would break the line.
std::string one_line(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (const char ch : s) {
    if (ch == '\n') {
      out += "\\n";
    } else if (ch == '\r') {
      out += "\\r";
    } else {
      out += ch;
    }
  }
  return out;
}

[[noreturn]] void fail(std::string_view message) {
  throw ConfigError(one_line(message));
}

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t");
  return s.substr(first, last - first + 1);
}

std::string position(const std::string& source, const toml::source_region& region) {
  if (region.begin.line == 0) return source;
  return source + ":" + std::to_string(region.begin.line) + ":" +
         std::to_string(region.begin.column);
}

// A --set argument as the user would retype it in a shell (abbreviated if long).
std::string shell_word(std::string_view whole) {
  const std::string arg = abbreviated(whole);
  const bool plain = !arg.empty() && std::all_of(arg.begin(), arg.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) ||
           std::string_view("_-.=+,:/@%").find(ch) != std::string_view::npos;
  });
  if (plain) return std::string(arg);
  std::string out = "'";
  for (const char ch : arg) {
    if (ch == '\'') {
      out += "'\\''";
    } else {
      out += ch;
    }
  }
  return out + "'";
}

// A TOML node in TOML syntax, for messages.
std::string format_node(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::integer:
      return std::to_string(node.as_integer()->get());
    case toml::node_type::floating_point:
      return format_real(node.as_floating_point()->get());
    case toml::node_type::boolean:
      return node.as_boolean()->get() ? "true" : "false";
    case toml::node_type::string:
      return toml_quoted(abbreviated(node.as_string()->get()));
    case toml::node_type::array: {
      std::vector<std::string> items;
      for (const toml::node& elem : *node.as_array()) items.push_back(format_node(elem));
      return "[" + join(items, ", ") + "]";
    }
    case toml::node_type::table: {
      std::vector<std::string> items;
      for (auto&& [k, v] : *node.as_table())
        items.push_back(std::string(k.str()) + " = " + format_node(v));
      return items.empty() ? "{}" : "{ " + join(items, ", ") + " }";
    }
    default: {
      std::ostringstream os;
      if (const auto* d = node.as_date()) os << *d;
      if (const auto* t = node.as_time()) os << *t;
      if (const auto* dt = node.as_date_time()) os << *dt;
      return os.str();
    }
  }
}

std::vector<std::string> split_key(std::string_view key) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const auto dot = key.find('.', start);
    parts.emplace_back(key.substr(start, dot - start));
    if (dot == std::string_view::npos) break;
    start = dot + 1;
  }
  return parts;
}

// "unknown key 'hydro.cels' (did you mean 'hydro.cells'?); allowed in [hydro]: cells, t_end, ..."
std::string unknown_key_message(const std::string& key) {
  std::string table;  // the deepest table of the schema that `key` is inside
  const std::vector<std::string> parts = split_key(key);
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::string next = table.empty() ? parts[i] : table + "." + parts[i];
    if (!is_schema_table(next)) break;
    table = next;
  }
  std::vector<std::string> candidates;
  for (const KeySpec& spec : case_schema()) {
    const std::string& k = spec.key;
    for (auto dot = k.find('.'); dot != std::string::npos; dot = k.find('.', dot + 1)) {
      const std::string table_path = k.substr(0, dot);  // the tables around the key
      if (std::find(candidates.begin(), candidates.end(), table_path) == candidates.end()) {
        candidates.push_back(table_path);
      }
    }
    candidates.push_back(k);
  }
  std::string message = "unknown key '" + abbreviated(key) + "'";
  if (const auto guess = closest_match(key, candidates))
    message += " (did you mean '" + *guess + "'?)";
  message += table.empty() ? "; allowed at top level: " : "; allowed in [" + table + "]: ";
  return message + join(schema_children(table), ", ");
}

// The value of `node` if it has the type of `spec` (an integer is accepted as a real).
std::optional<Value> extract(const KeySpec& spec, const toml::node& node) {
  const auto real_of = [](const toml::node& n) -> std::optional<double> {
    if (const auto* f = n.as_floating_point()) return f->get();
    if (const auto* i = n.as_integer()) return static_cast<double>(i->get());
    return std::nullopt;
  };
  switch (spec.type) {
    case ValueType::real:
      if (const auto x = real_of(node)) return Value(*x);
      return std::nullopt;
    case ValueType::integer:
      if (const auto* i = node.as_integer()) return Value(static_cast<long long>(i->get()));
      return std::nullopt;
    case ValueType::boolean:
      if (const auto* b = node.as_boolean()) return Value(b->get());
      return std::nullopt;
    case ValueType::string:
      if (const auto* s = node.as_string()) return Value(s->get());
      return std::nullopt;
    case ValueType::real_array: {
      const auto* arr = node.as_array();
      if (!arr) return std::nullopt;
      std::vector<double> xs;
      for (const toml::node& elem : *arr) {
        const auto x = real_of(elem);
        if (!x) return std::nullopt;
        xs.push_back(*x);
      }
      return Value(std::move(xs));
    }
    case ValueType::integer_array: {
      const auto* arr = node.as_array();
      if (!arr) return std::nullopt;
      std::vector<long long> xs;
      for (const toml::node& elem : *arr) {
        const auto* i = elem.as_integer();
        if (!i) return std::nullopt;
        xs.push_back(static_cast<long long>(i->get()));
      }
      return Value(std::move(xs));
    }
    case ValueType::real_table: {
      const auto* table = node.as_table();
      if (!table) return std::nullopt;
      RealTable named;
      for (auto&& [k, v] : *table) {
        const auto x = real_of(v);
        if (!x) return std::nullopt;
        named[std::string(k.str())] = *x;
      }
      return Value(std::move(named));
    }
    case ValueType::string_array: {
      const auto* arr = node.as_array();
      if (!arr) return std::nullopt;
      std::vector<std::string> xs;
      for (const toml::node& elem : *arr) {
        const auto* str = elem.as_string();
        if (!str) return std::nullopt;
        xs.push_back(str->get());
      }
      return Value(std::move(xs));
    }
  }
  return std::nullopt;
}

Value default_value(const KeySpec& spec, const std::string& source) {
  switch (spec.default_value.kind) {
    case Default::Kind::file_stem: {
      // A folder name: bytes that are not UTF-8 text or are control characters become '_'.
      std::string stem = utf8_repaired(std::filesystem::path(source).stem().string(), '_');
      for (char& ch : stem) {
        const auto u = static_cast<unsigned char>(ch);
        if (u < 0x20 || u == 0x7f || ch == '\\') ch = '_';
      }
      if (stem.size() > kMaxNameBytes) stem = utf8_repaired(stem.substr(0, kMaxNameBytes), '_');
      return Value(stem.empty() || stem == "." || stem == ".." ? std::string("case") : stem);
    }
    case Default::Kind::empty_array:
      if (spec.type == ValueType::integer_array) return Value(std::vector<long long>{});
      if (spec.type == ValueType::string_array) return Value(std::vector<std::string>{});
      return Value(std::vector<double>{});
    case Default::Kind::list_of_key:  // resolved where the other key's value is known
      throw std::logic_error("case schema: " + spec.key + " takes its default from " +
                             spec.default_value.key);
    case Default::Kind::value: {
      const Value& v = spec.default_value.value;
      if (spec.type == ValueType::real && std::holds_alternative<long long>(v)) {
        return Value(static_cast<double>(std::get<long long>(v)));
      }
      if (v.index() != static_cast<std::size_t>(spec.type)) {
        throw std::logic_error("case schema: the default of " + spec.key + " is not " +
                               type_phrase(spec.type));
      }
      return v;
    }
    case Default::Kind::required:
      break;
  }
  throw std::logic_error("case schema: " + spec.key + " has no default");
}

// ---------------------------------------------------------------------------------------------
// --set KEY=VALUE
// ---------------------------------------------------------------------------------------------
struct Override {
  std::string where;  // "--set physics.K=1e-3"
  std::string key;
  toml::table holder;  // holds the value as "v"
  const toml::node& node() const { return *holder.get("v"); }
};

bool valid_dotted_key(std::string_view key) {
  if (key.find('.') == std::string_view::npos) return false;
  for (const std::string& part : split_key(key)) {
    if (part.empty()) return false;
    if (std::any_of(part.begin(), part.end(), [](char ch) {
          return std::isspace(static_cast<unsigned char>(ch)) || ch == '=' || ch == '"' ||
                 ch == '\'';
        })) {
      return false;
    }
  }
  return true;
}

Override parse_override(const std::string& arg) {
  const auto eq = arg.find('=');
  const std::string_view key =
      eq == std::string::npos ? std::string_view() : trim(std::string_view(arg).substr(0, eq));
  if (eq == std::string::npos || !valid_dotted_key(key)) {
    std::string quoted = "'";
    for (const char ch : abbreviated(arg))
      quoted += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    fail("--set " + quoted + "': malformed override; expected KEY=VALUE with a dotted KEY, e.g. " +
         "--set physics.K=1e-3");
  }
  Override o;
  o.where = "--set " + shell_word(arg);
  o.key = std::string(key);
  const KeySpec* spec = find_key_spec(o.key);
  if (!spec) {
    if (is_schema_table(o.key)) {
      fail(o.where + ": '" + o.key +
           "' is a table, not a key; set one of its keys: " + join(schema_children(o.key), ", "));
    }
    fail(o.where + ": " + unknown_key_message(o.key));
  }
  const std::string text(trim(std::string_view(arg).substr(eq + 1)));
  bool parsed = false;
  try {
    o.holder = toml::parse("v = " + text, std::string_view("--set"));
    parsed = o.holder.size() == 1 && o.holder.get("v") != nullptr;
  } catch (const toml::parse_error&) {
    parsed = false;
  }
  // Not TOML: a bare string. For string keys a bare number or boolean is a string too
  // (--set case.name=2024), so that quoting is only needed for strings with TOML syntax.
  const toml::node* node = parsed ? o.holder.get("v") : nullptr;
  const bool bare_scalar_for_string = spec->type == ValueType::string && node &&
                                      !node->is_string() && !node->is_array() && !node->is_table();
  if (!parsed || bare_scalar_for_string) {
    o.holder = toml::table{};
    o.holder.insert_or_assign("v", text);
  }
  return o;
}

// ---------------------------------------------------------------------------------------------
// Validation of the parsed file: one problem is reported, the first in the file.
// ---------------------------------------------------------------------------------------------
struct Problem {
  std::tuple<int, std::size_t, std::size_t, std::size_t> order;  // group, line, column, sequence
  std::string message;
};

class Problems {
 public:
  void add(int group, const toml::source_region& region, std::string message) {
    list_.push_back(
        {{group, region.begin.line, region.begin.column, list_.size()}, std::move(message)});
  }
  void add(int group, std::string message) {
    list_.push_back({{group, 0, 0, list_.size()}, std::move(message)});
  }
  void throw_first() const {
    if (list_.empty()) return;
    const auto first =
        std::min_element(list_.begin(), list_.end(),
                         [](const Problem& a, const Problem& b) { return a.order < b.order; });
    fail(first->message);
  }

 private:
  std::vector<Problem> list_;
};

// Collects the leaves of the file that are schema keys; unknown keys and tables that are not
// tables are problems.
void walk(const toml::table& table, const std::string& path, const std::string& source,
          std::map<std::string, const toml::node*>& leaves, Problems& problems) {
  for (auto&& [k, v] : table) {
    const std::string full =
        path.empty() ? std::string(k.str()) : path + "." + std::string(k.str());
    if (find_key_spec(full)) {
      leaves[full] = &v;
    } else if (is_schema_table(full)) {
      if (const auto* sub = v.as_table()) {
        walk(*sub, full, source, leaves, problems);
      } else {
        problems.add(0, v.source(),
                     position(source, v.source()) + ": " + full + " = " + format_node(v) +
                         ": expected a table [" + full + "] with keys " +
                         join(schema_children(full), ", "));
      }
    } else {
      problems.add(0, k.source(), position(source, k.source()) + ": " + unknown_key_message(full));
    }
  }
}

}  // namespace

void report_input_error(const ConfigError& error) {
  for (const char* variable : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"}) {
    const char* rank = std::getenv(variable);
    if (rank && std::string_view(rank) != "0") return;
  }
  std::cerr << "granvv: error: " << error.what() << "\n";
}

// ---------------------------------------------------------------------------------------------
// CaseConfig
// ---------------------------------------------------------------------------------------------
CaseConfig CaseConfig::from_file(const std::filesystem::path& file,
                                 const std::vector<std::string>& sets) {
  const std::string name = file.string();
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (!std::filesystem::exists(status)) fail("case file '" + name + "' does not exist");
  if (std::filesystem::is_directory(status)) {
    fail("case file '" + name + "' is a directory, not a TOML file");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) fail("cannot open case file '" + name + "'");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) fail("cannot read case file '" + name + "'");
  return from_string(text.str(), name, sets);
}

CaseConfig CaseConfig::from_string(std::string_view toml_text, std::string source_name,
                                   const std::vector<std::string>& sets) {
  CaseConfig config;
  config.source_ = source_name.empty() ? std::string("<string>") : std::move(source_name);
  config.sets_ = sets;
  const std::string& source = config.source_;

  toml::table file;
  try {
    file = toml::parse(toml_text, std::string_view(source));
  } catch (const toml::parse_error& e) {
    fail(position(source, e.source()) + ": TOML syntax error: " + std::string(e.description()));
  }

  // Overrides: a malformed one or an unknown key stops at once.
  std::vector<Override> overrides;
  for (const std::string& arg : sets) overrides.push_back(parse_override(arg));

  Problems problems;
  std::map<std::string, const toml::node*> leaves;
  walk(file, "", source, leaves, problems);

  for (const KeySpec& spec : case_schema()) {
    const toml::node* node = nullptr;
    std::string where;
    int group = 0;
    toml::source_region region;
    for (const Override& o : overrides) {  // the last --set of a key wins
      if (o.key == spec.key) {
        node = &o.node();
        where = o.where;
        group = 1;
      }
    }
    if (!node) {
      if (const auto it = leaves.find(spec.key); it != leaves.end()) {
        node = it->second;
        region = node->source();
        where = position(source, region);
      }
    }
    if (!node) {
      if (spec.default_value.kind == Default::Kind::required) {
        problems.add(2, "missing required key " + spec.key + " in " + source + "; expected " +
                            expected_phrase(spec) + " (" + spec.description + ")");
        continue;
      }
      if (spec.default_value.kind == Default::Kind::list_of_key) {
        // The other key comes earlier in the schema; if it was refused, so is nothing here.
        const auto other = config.values_.find(spec.default_value.key);
        if (other == config.values_.end()) continue;
        config.values_.emplace(
            spec.key, Value(std::vector<std::string>{std::get<std::string>(other->second)}));
      } else {
        config.values_.emplace(spec.key, default_value(spec, source));
      }
      config.origins_.emplace(spec.key, "default");
      continue;
    }
    const std::optional<Value> value = extract(spec, *node);
    const std::string prefix =
        where + ": " + spec.key + " = " + abbreviated(format_node(*node), 200) + ": ";
    if (!value) {
      problems.add(group, region, prefix + "expected " + expected_phrase(spec));
      continue;
    }
    if (const auto why = constraint_violation(spec, *value)) {
      problems.add(group, region, prefix + *why);
      continue;
    }
    config.values_.emplace(spec.key, *value);
    config.origins_.emplace(spec.key, where);
  }
  problems.throw_first();
  config.reconcile_restitution();

  for (const CrossCheck& check : case_cross_checks()) {
    if (const auto violation = check.check(config)) {
      const std::string origin = config.origin(violation->key);
      fail((origin == "default" ? source : origin) + ": " + violation->key + " = " +
           abbreviated(format_value(config.value(violation->key)), 200) + ": " +
           violation->message);
    }
  }
  return config;
}

// The particles' restitution md.restitution and the hydro's q are one gas's, r = 1 - 2q
// (docs/physics.md §1). With both parts running, the key the user set last decides and the other
// follows, so that a sweep over either moves the particles, the hydro and every compared closure
// together; given with the same precedence (both in the case file) they must agree. md.restitution
// = 0 means "from q". An elastic gas (r = 1) has no q > 0, the hydro's scaled units need cooling:
// there the hydro keeps physics.q.
void CaseConfig::reconcile_restitution() {
  if (!boolean("md.enabled") || !boolean("hydro.enabled")) return;
  const double r = real("md.restitution"), q = real("physics.q");
  if (!(r > 0.0 && r < 1.0) || std::abs(0.5 * (1.0 - r) - q) <= 1e-12) return;
  const int r_rank = origin_precedence("md.restitution"), q_rank = origin_precedence("physics.q");
  if (r_rank == q_rank) {
    fail(origin("md.restitution") + ": md.restitution = " + format_real(r) +
         ": the particles' restitution must be 1 - 2 physics.q = " + format_real(1.0 - 2.0 * q) +
         " (physics.q = " + format_real(q) + " from " + origin("physics.q") +
         "): they are one gas; give one of them");
  }
  if (r_rank > q_rank) {
    values_["physics.q"] = 0.5 * (1.0 - r);
    origins_["physics.q"] = origin("md.restitution");
  } else {
    values_["md.restitution"] = 1.0 - 2.0 * q;
    origins_["md.restitution"] = origin("physics.q");
  }
}

const Value& CaseConfig::value(std::string_view key) const {
  const auto it = values_.find(key);
  if (it == values_.end()) {
    throw std::logic_error("CaseConfig: '" + std::string(key) +
                           "' is not a key of the case schema (scene/case_schema.cpp)");
  }
  return it->second;
}

const Value& CaseConfig::checked(std::string_view key, ValueType type) const {
  const KeySpec* spec = find_key_spec(key);
  if (!spec) {
    throw std::logic_error("CaseConfig: '" + std::string(key) +
                           "' is not a key of the case schema (scene/case_schema.cpp)");
  }
  if (spec->type != type) {
    throw std::logic_error("CaseConfig: " + spec->key + " is " + type_phrase(spec->type) +
                           ", not " + type_phrase(type));
  }
  return value(key);
}

double CaseConfig::real(std::string_view key) const {
  return std::get<double>(checked(key, ValueType::real));
}
long long CaseConfig::integer(std::string_view key) const {
  return std::get<long long>(checked(key, ValueType::integer));
}

namespace {

// The value of an integer key as an int. The schema bounds every integer key within an int
// (case_schema.cpp), so a value outside is a key that escaped validation: refused, named.
int as_int(const KeySpec& spec, const std::string& origin, long long value) {
  const Constraint& c = spec.constraint;
  const bool fits = value >= std::numeric_limits<int>::min() &&
                    value <= std::numeric_limits<int>::max() &&
                    (!c.min || static_cast<double>(value) >= *c.min) &&
                    (!c.max || static_cast<double>(value) <= *c.max);
  if (!fits) {
    fail(origin + ": " + spec.key + " = " + std::to_string(value) + ": must be " +
         expected_phrase(spec));
  }
  return static_cast<int>(value);
}

}  // namespace

int CaseConfig::int_value(std::string_view key) const {
  const long long v = integer(key);
  return as_int(*find_key_spec(key), origin(key), v);
}

std::vector<int> CaseConfig::int_values(std::string_view key) const {
  std::vector<int> out;
  for (const long long v : integers(key))
    out.push_back(as_int(*find_key_spec(key), origin(key), v));
  return out;
}
bool CaseConfig::boolean(std::string_view key) const {
  return std::get<bool>(checked(key, ValueType::boolean));
}
std::string CaseConfig::string(std::string_view key) const {
  return std::get<std::string>(checked(key, ValueType::string));
}
std::vector<double> CaseConfig::reals(std::string_view key) const {
  return std::get<std::vector<double>>(checked(key, ValueType::real_array));
}
std::vector<long long> CaseConfig::integers(std::string_view key) const {
  return std::get<std::vector<long long>>(checked(key, ValueType::integer_array));
}
std::vector<std::string> CaseConfig::strings(std::string_view key) const {
  return std::get<std::vector<std::string>>(checked(key, ValueType::string_array));
}

std::string CaseConfig::name() const {
  return string("case.name");
}

std::string CaseConfig::origin(std::string_view key) const {
  value(key);  // logic_error for keys outside the schema
  const auto it = origins_.find(key);
  return it == origins_.end() ? std::string("default") : it->second;
}

int CaseConfig::origin_precedence(std::string_view key) const {
  const std::string o = origin(key);
  if (o.rfind("--set", 0) == 0) {  // a later --set ranks above an earlier one
    int rank = 2;
    for (std::size_t i = 0; i < sets_.size(); ++i) {
      if (trim(std::string_view(sets_[i]).substr(0, sets_[i].find('='))) == key) rank = 2 + int(i);
    }
    return rank;
  }
  return o == "default" ? 0 : 1;
}

std::vector<std::pair<std::string, std::string>> CaseConfig::flattened() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [key, v] : values_) out.emplace_back(key, format_value(v));
  return out;  // std::map: sorted by key
}

std::string CaseConfig::resolved_toml() const {
  // TOML comments may not hold control characters.
  const auto comment = [](std::string_view s) {
    std::string out = utf8_repaired(s, '?');
    for (char& ch : out) {
      const auto u = static_cast<unsigned char>(ch);
      if ((u < 0x20 && ch != '\t') || u == 0x7f) ch = '?';
    }
    return out;
  };
  std::ostringstream os;
  os << "# Resolved case '" << comment(name()) << "' from " << comment(source_) << "\n";
  for (const std::string& s : sets_) os << "#   --set " << comment(s) << "\n";
  os << "# Every key of the case schema: defaults filled in, overrides applied.\n";

  std::vector<std::string> sections;  // in schema order; top-level keys (section "") first
  for (const KeySpec& spec : case_schema()) {
    if (std::find(sections.begin(), sections.end(), spec.section()) == sections.end()) {
      sections.push_back(spec.section());
    }
  }
  std::stable_partition(sections.begin(), sections.end(),
                        [](const std::string& s) { return s.empty(); });
  for (const std::string& section : sections) {
    if (!section.empty()) os << "\n[" << section << "]\n";
    for (const KeySpec& spec : case_schema()) {
      if (spec.section() != section) continue;
      std::string line = spec.leaf() + " = " + format_value(values_.at(spec.key));
      if (line.size() < 40) line.resize(40, ' ');
      os << line << "  # " << comment(spec.description) << "; " << comment(expected_phrase(spec))
         << "\n";
    }
  }
  return os.str();
}

namespace {

// The models of `selector` ("md.engine", "hydro.closure") that the case runs; nullopt when it
// runs that part not at all.
std::optional<std::vector<std::string>> models_run(const CaseConfig& c, const std::string& selector,
                                                   RunningCommand command) {
  if (selector == "md.engine") {
    if (!c.boolean("md.enabled")) return std::nullopt;
    // The atlas weighs every registered engine on a particle scene (models/family_particles).
    if (command == RunningCommand::atlas) return md::particle_engine_names();
    return std::vector<std::string>{c.string("md.engine")};
  }
  if (!c.boolean("hydro.enabled")) return std::nullopt;
  std::vector<std::string> closures = {c.string("hydro.closure")};
  if (c.boolean("compare.enabled")) closures = c.strings("compare.closures");
  if (command == RunningCommand::atlas) {
    for (const std::string& name : hydro::closure_names()) {
      if (hydro::closure_on_every_ladder(name)) closures.push_back(name);
    }
  }
  return closures;
}

}  // namespace

void refuse_keys_of_models_not_run(const CaseConfig& c, RunningCommand command) {
  for (const KeySpec& spec : case_schema()) {
    const auto owner = key_owner(spec.key);
    if (!owner || c.origin(spec.key) == "default") continue;
    if (c.value(spec.key) == spec.default_value.value) continue;
    const auto run = models_run(c, owner->selector, command);
    if (!run || std::find(run->begin(), run->end(), owner->model) != run->end()) continue;
    // The key that says which models run: the selector, or the list of compared closures.
    const std::string chosen = owner->selector == "hydro.closure" && c.boolean("compare.enabled")
                                   ? "compare.closures"
                                   : owner->selector;
    const std::string origin = c.origin(chosen);
    const std::string runs = chosen + " = " + format_value(c.value(chosen)) +
                             (origin == "default" ? " (default)" : " (from " + origin + ")");
    fail(c.origin(spec.key) + ": " + spec.key + " = " +
         abbreviated(format_value(c.value(spec.key)), 80) + ": a key of " + owner->selector +
         " = " + toml_quoted(owner->model) + ", but this case runs " + runs);
  }
}

}  // namespace granvv::app
