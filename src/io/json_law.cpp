// JSON → library types for the files of docs/problem-file.md (and the scene file), with messages
// that name the key as the file spells it. The library's own checks (ImpactLaw::validate, the
// potentials' constructors, the registry) stay the authority on values; this file only adds what
// JSON brings: types, shapes, key names, and keys nobody asked for.
#include "io/detail/json_law.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <set>

#include "core/detail/validate.hpp"
#include "fremond/core/error.hpp"

namespace fremond::io::detail {

using fremond::detail::format_number;

std::string key_path(const std::string& where, std::string_view key) {
  // An empty key is legal JSON; quoted, it still shows in "<key>: <reason>".
  const std::string k = key.empty() ? std::string("\"\"") : std::string(key);
  return where.empty() ? k : where + "." + k;
}

std::string index_path(const std::string& where, std::size_t i) {
  return where + "[" + std::to_string(i) + "]";
}

std::string describe_json(const json& j) {
  switch (j.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return std::string("a boolean (") + (j.get<bool>() ? "true" : "false") + ")";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return "the number " + format_number(j.get<double>());
    case json::value_t::string: {
      std::string s = j.get<std::string>();
      if (s.size() > 40) s = s.substr(0, 37) + "...";
      return "a string " + json(s).dump(-1, ' ', false, json::error_handler_t::replace);
    }
    case json::value_t::array:
      return "a list of " + std::to_string(j.size()) + (j.size() == 1 ? " entry" : " entries");
    case json::value_t::object:
      return "an object";
    default:
      return "a value of type " + std::string(j.type_name());
  }
}

namespace {

// Builds the document like nlohmann's own DOM parser, but knows at every moment which key it is
// reading, so that a syntax error or a number overflow names that key, and refuses a key given
// twice (json's object would keep one of them without a word).
class PathTrackingBuilder final : public nlohmann::json_sax<json> {
 public:
  PathTrackingBuilder(json& root, const std::string& root_name)
      : root_(root), root_name_(root_name) {}

  bool null() override { return add(json(nullptr)); }
  bool boolean(bool v) override { return add(json(v)); }
  bool number_integer(number_integer_t v) override { return add(json(v)); }
  bool number_unsigned(number_unsigned_t v) override { return add(json(v)); }
  bool number_float(number_float_t v, const string_t&) override { return add(json(v)); }
  bool string(string_t& v) override { return add(json(std::move(v))); }
  bool binary(binary_t& v) override { return add(json(json::binary_t(std::move(v)))); }
  bool start_object(std::size_t) override { return open(json::object()); }
  bool key(string_t& k) override {
    Frame& f = frames_.back();
    if (!f.keys.insert(k).second) {
      fail(key_path(container_path(), k), "duplicate key (given more than once)");
      return false;
    }
    f.key = k;
    f.value_read = false;
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(json::array()); }
  bool end_array() override { return close(); }

  bool parse_error(std::size_t, const std::string& token, const json::exception& ex) override {
    std::string at = container_path();
    std::string after;
    if (!frames_.empty()) {
      const Frame& f = frames_.back();
      if (f.value->is_array()) {
        at = index_path(at, f.value->size());  // the next element
      } else if (!f.keys.empty()) {
        if (f.value_read)  // between two members: say where, without blaming the last key
          after = " (after the value of \"" + f.key + "\")";
        else
          at = key_path(at, f.key);
      }
    }
    // A pathological nesting depth would make the name longer than the message is useful.
    if (at.size() > 200) at = at.substr(0, 200) + "...";
    const std::string name = at.empty() ? root_name_ : at;
    if (ex.id == 406) {  // out_of_range.406: a number beyond the range of a double
      fail(name, "must be a finite number, got " + token + " (out of the range of a double)");
      return false;
    }
    // Drop nlohmann's "[json.exception.parse_error.101] " tag; keep line, column and reason.
    std::string what = ex.what();
    if (const auto end = what.find("] "); what.rfind("[json.exception", 0) == 0 && end != what.npos)
      what = what.substr(end + 2);
    fail(name, "not valid JSON: " + what + after);
    return false;
  }

  /// The refusal, once parsing stopped.
  const std::optional<InvalidArgument>& error() const { return error_; }

 private:
  struct Frame {
    json* value;
    std::string key;          // objects: the last key read
    bool value_read = false;  // objects: the value of `key` is complete
    std::set<std::string> keys;
  };

  // Where the next value goes: the root, the pending key of an object, or the end of an array.
  // Pointers stay valid: an object's map never moves its nodes, and an array only grows while its
  // own frame is on top, i.e. after the child frame above it has been closed.
  json* slot() {
    if (frames_.empty()) return &root_;
    Frame& f = frames_.back();
    if (f.value->is_object()) return &(*f.value)[f.key];
    f.value->push_back(json());
    return &f.value->back();
  }
  bool add(json v) {
    *slot() = std::move(v);
    value_done();
    return true;
  }
  bool open(json empty) {
    json* v = slot();
    *v = std::move(empty);
    frames_.push_back({v, {}, false, {}});
    return true;
  }
  bool close() {
    frames_.pop_back();
    value_done();
    return true;
  }
  void value_done() {
    if (!frames_.empty()) frames_.back().value_read = true;
  }
  // The path of the innermost container: `a.b[2]` (each outer container's current member).
  // A document that is a list has no key: its elements are named `root[i]`.
  std::string container_path() const {
    std::string p = !frames_.empty() && frames_[0].value->is_array() ? root_name_ : "";
    for (std::size_t i = 0; i + 1 < frames_.size(); ++i) {
      const Frame& f = frames_[i];
      p = f.value->is_object() ? key_path(p, f.key) : index_path(p, f.value->size() - 1);
    }
    return p;
  }
  void fail(const std::string& name, const std::string& reason) {
    if (!error_) error_.emplace(name, reason);
  }

  json& root_;
  std::string root_name_;
  std::vector<Frame> frames_;
  std::optional<InvalidArgument> error_;
};

}  // namespace

json parse_json(std::string_view text, const std::string& root) {
  if (std::all_of(text.begin(), text.end(),
                  [](char ch) { return ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r'; }))
    throw InvalidArgument(root, "empty input (expected a JSON document)");
  // nlohmann's iterator input ends at a NUL byte, so text after one would be silently ignored:
  // a NUL is never part of JSON text (RFC 8259 §2), so refuse it where it is.
  if (const auto nul = text.find('\0'); nul != std::string_view::npos)
    throw InvalidArgument(root, "not valid JSON: a NUL byte at offset " + std::to_string(nul));
  json doc;
  PathTrackingBuilder builder(doc, root);
  const bool ok = json::sax_parse(text.begin(), text.end(), &builder);
  if (builder.error()) throw *builder.error();
  if (!ok) throw InvalidArgument(root, "not valid JSON");
  return doc;
}

void require_object(const json& j, const std::string& where) {
  if (!j.is_object())
    throw InvalidArgument(where, "must be a JSON object, got " + describe_json(j));
}

void check_keys(const json& obj, const std::string& where,
                std::initializer_list<std::string_view> allowed, const std::string& context) {
  for (const auto& item : obj.items()) {
    if (std::find(allowed.begin(), allowed.end(), item.key()) != allowed.end()) continue;
    std::string known;
    for (auto k : allowed) known += (known.empty() ? "" : ", ") + std::string(k);
    throw InvalidArgument(key_path(where, item.key()),
                          "unknown key of " + context + " (known: " + known + ")");
  }
}

const json& required_key(const json& obj, const std::string& where, std::string_view key) {
  const auto it = obj.find(key);
  if (it == obj.end()) throw InvalidArgument(key_path(where, key), "missing (required)");
  return *it;
}

const json* optional_key(const json& obj, std::string_view key) {
  const auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

std::string string_from_json(const json& j, const std::string& key) {
  if (!j.is_string()) throw InvalidArgument(key, "must be a string, got " + describe_json(j));
  return j.get<std::string>();
}

double number_from_json(const json& j, const std::string& key) {
  // nlohmann keeps booleans apart from numbers, so `true` is refused here, not read as 1.
  if (!j.is_number()) throw InvalidArgument(key, "must be a number, got " + describe_json(j));
  const double v = j.get<double>();
  fremond::detail::require_finite(key, v);
  return v;
}

std::vector<double> number_or_list(const json& j, const std::string& key, int contacts) {
  if (!j.is_array()) {
    if (!j.is_number())
      throw InvalidArgument(
          key, "must be a number or a list of numbers (one per contact), got " + describe_json(j));
    return {number_from_json(j, key)};
  }
  if (j.empty()) throw InvalidArgument(key, "an empty list: give one value or one per contact");
  if (contacts >= 0 && j.size() != 1 && static_cast<int>(j.size()) != contacts)
    throw InvalidArgument(key, "needs one value or one per contact (" + std::to_string(contacts) +
                                   "), got a list of " + std::to_string(j.size()));
  std::vector<double> out;
  out.reserve(j.size());
  for (std::size_t i = 0; i < j.size(); ++i)
    out.push_back(number_from_json(j[i], index_path(key, i)));
  return out;
}

VectorX vector_from_json(const json& j, const std::string& key) {
  if (!j.is_array())
    throw InvalidArgument(key, "must be a list of numbers, got " + describe_json(j));
  VectorX v(static_cast<Eigen::Index>(j.size()));
  for (std::size_t i = 0; i < j.size(); ++i)
    v(static_cast<Eigen::Index>(i)) = number_from_json(j[i], index_path(key, i));
  return v;
}

MatrixX matrix_from_json(const json& j, const std::string& key) {
  if (!j.is_array())
    throw InvalidArgument(key, "must be a matrix (a list of rows), got " + describe_json(j));
  const auto rows = static_cast<Eigen::Index>(j.size());
  Eigen::Index cols = 0;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const json& row = j[i];
    const std::string row_key = index_path(key, i);
    if (!row.is_array())
      throw InvalidArgument(row_key,
                            "must be a list of numbers (a matrix row), got " + describe_json(row));
    if (i == 0) cols = static_cast<Eigen::Index>(row.size());
    if (static_cast<Eigen::Index>(row.size()) != cols)
      throw InvalidArgument(row_key, "has " + std::to_string(row.size()) + " entries but " +
                                         index_path(key, 0) + " has " + std::to_string(cols) +
                                         " (every row needs the same length)");
  }
  MatrixX m(rows, cols);
  for (Eigen::Index r = 0; r < rows; ++r)
    for (Eigen::Index c = 0; c < cols; ++c)
      m(r, c) = number_from_json(
          j[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)],
          index_path(index_path(key, static_cast<std::size_t>(r)), static_cast<std::size_t>(c)));
  return m;
}

namespace {

// The checks of ImpactLaw::validate, but with the key names of the file, element by element.
std::vector<double> restitution(const json& j, const std::string& key, int contacts) {
  std::vector<double> e = number_or_list(j, key, contacts);
  for (std::size_t i = 0; i < e.size(); ++i)
    fremond::detail::require_in_unit_interval(
        e.size() == 1 && !j.is_array() ? key : index_path(key, i), e[i]);
  return e;
}
std::vector<double> friction(const json& j, const std::string& key, int contacts) {
  std::vector<double> mu = number_or_list(j, key, contacts);
  for (std::size_t i = 0; i < mu.size(); ++i)
    fremond::detail::require_finite_at_least(
        mu.size() == 1 && !j.is_array() ? key : index_path(key, i), mu[i], 0.0);
  return mu;
}

// The reason part of an InvalidArgument ("name: reason"), to rename the key it names.
std::string reason_of(const InvalidArgument& e) {
  return std::string(e.what()).substr(e.name().size() + 2);
}

// "where.k: <reason>" from the registry or a constructor, renamed to the list element when the
// parameter was a per-contact list: "where.k[1]: <reason>".
[[noreturn]] void rethrow_for_contact(const InvalidArgument& e, const std::string& where,
                                      const std::map<std::string, std::vector<double>>& params,
                                      std::size_t contact) {
  const std::string prefix = where + ".";
  if (e.name().rfind(prefix, 0) == 0) {
    const auto it = params.find(e.name().substr(prefix.size()));
    if (it != params.end()) {
      if (it->second.size() == 1) throw e;  // the same value for every contact
      throw InvalidArgument(index_path(e.name(), contact), reason_of(e));
    }
  }
  throw InvalidArgument(e.name(), reason_of(e) + " (contact " + std::to_string(contact) + ")");
}

// One potential {"potential": NAME, parameters...}, every parameter a number or one per contact.
PerContactPotential potential_from_json(const json& j, const std::string& where, int contacts,
                                        const PotentialRegistry& registry) {
  require_object(j, where);
  const std::string name_key = key_path(where, "potential");
  const std::string name = string_from_json(required_key(j, where, "potential"), name_key);
  const PotentialKind* kind = nullptr;
  try {
    kind = &registry.kind(name);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(name_key, reason_of(e));
  }
  // Keys first, so that a misspelt parameter is reported as such and not as a bad value.
  std::vector<std::string_view> allowed{"potential"};
  for (const auto& r : kind->required) allowed.push_back(r);
  for (const auto& [o, v] : kind->optional) allowed.push_back(o);
  for (const auto& item : j.items()) {
    if (std::find(allowed.begin(), allowed.end(), item.key()) != allowed.end()) continue;
    std::string known;
    for (auto k : allowed) known += (known.empty() ? "" : ", ") + std::string(k);
    throw InvalidArgument(
        key_path(where, item.key()),
        "unknown key: not a parameter of potential '" + name + "' (known: " + known + ")");
  }
  for (const auto& r : kind->required)
    if (!j.contains(r))
      throw InvalidArgument(key_path(where, r), "missing, required by potential '" + name + "'");

  std::map<std::string, std::vector<double>> lists;
  bool per_contact = false;
  for (const auto& item : j.items()) {
    if (item.key() == "potential") continue;
    lists[item.key()] = number_or_list(item.value(), key_path(where, item.key()), contacts);
    per_contact = per_contact || item.value().is_array();
  }
  auto parameters_of = [&](std::size_t contact) {
    PotentialParameters p;
    for (const auto& [k, v] : lists) p[k] = v.size() == 1 ? v[0] : v[contact];
    return p;
  };
  PerContactPotential out;
  if (!per_contact) {
    out.potentials.emplace_back(registry.make(name, parameters_of(0), where));
    return out;
  }
  // A list of one value is the same for every contact; only a longer list makes one potential per
  // contact, so a problem with one contact and `"k": [2]` still has one potential.
  std::size_t count = 1;
  for (const auto& [k, v] : lists) count = std::max(count, v.size());
  for (std::size_t i = 0; i < count; ++i) {
    try {
      out.potentials.emplace_back(registry.make(name, parameters_of(i), where));
    } catch (const InvalidArgument& e) {
      rethrow_for_contact(e, where, lists, i);
    }
  }
  return out;
}

LawType law_type_from_json(const json& j, const std::string& where) {
  const std::string key = key_path(where, "type");
  const std::string name = string_from_json(required_key(j, where, "type"), key);
  try {
    return law_type_from_string(name);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(key, reason_of(e));
  }
}

}  // namespace

ImpactLaw law_from_json(const json& j, int contacts, const PotentialRegistry& registry,
                        const std::string& where) {
  require_object(j, where);
  const LawType type = law_type_from_json(j, where);
  const std::string context = "a '" + std::string(to_string(type)) + "' law";
  ImpactLaw law;
  switch (type) {
    case LawType::newton:
    case LawType::poisson: {
      check_keys(j, where, {"type", "e"}, context);
      const auto e = restitution(required_key(j, where, "e"), key_path(where, "e"), contacts);
      law = type == LawType::newton ? ImpactLaw::newton(e) : ImpactLaw::poisson(e);
      break;
    }
    case LawType::newton_coulomb:
    case LawType::poisson_coulomb: {
      check_keys(j, where, {"type", "e", "mu"}, context);
      const auto e = restitution(required_key(j, where, "e"), key_path(where, "e"), contacts);
      const auto mu = friction(required_key(j, where, "mu"), key_path(where, "mu"), contacts);
      law = type == LawType::newton_coulomb ? ImpactLaw::newton_coulomb(e, mu)
                                            : ImpactLaw::poisson_coulomb(e, mu);
      break;
    }
    case LawType::fremond: {
      check_keys(j, where, {"type", "normal", "tangential"}, context);
      const std::string normal_key = key_path(where, "normal");
      const json& normal = required_key(j, where, "normal");
      // Coulomb is a law on the tangential velocity, not a potential of the normal one
      // (docs/laws.md).
      if (normal.is_object() && normal.contains("potential") && normal["potential"] == "coulomb")
        throw InvalidArgument(key_path(normal_key, "potential"),
                              "'coulomb' is a tangential law only (use it under " +
                                  key_path(where, "tangential") + ")");
      auto normal_potential = potential_from_json(normal, normal_key, contacts, registry);
      const json* tangential = optional_key(j, "tangential");
      if (!tangential) {  // docs/problem-file.md: omitted means no tangential percussion
        law = ImpactLaw::fremond(std::move(normal_potential));
        break;
      }
      const std::string tkey = key_path(where, "tangential");
      require_object(*tangential, tkey);
      const std::string tname = string_from_json(required_key(*tangential, tkey, "potential"),
                                                 key_path(tkey, "potential"));
      if (tname == "coulomb") {
        check_keys(*tangential, tkey, {"potential", "mu"}, "the tangential law 'coulomb'");
        const auto mu =
            friction(required_key(*tangential, tkey, "mu"), key_path(tkey, "mu"), contacts);
        law = ImpactLaw::fremond_coulomb(std::move(normal_potential), mu);
      } else {
        law = ImpactLaw::fremond(std::move(normal_potential),
                                 potential_from_json(*tangential, tkey, contacts, registry));
      }
      break;
    }
  }
  // The library's own check stays the last word; its messages say "law.…", renamed to `where`.
  try {
    law.validate(contacts);
  } catch (const InvalidArgument& e) {
    std::string name = e.name();
    if (name.rfind("law", 0) == 0) name = where + name.substr(3);
    throw InvalidArgument(name, reason_of(e));
  }
  return law;
}

}  // namespace fremond::io::detail
