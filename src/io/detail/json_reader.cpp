// Reading JSON with messages that name the key as the file spells it (detail/json_reader.hpp).
#include "io/detail/json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
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
  refuse_unknown_keys(obj, where, std::vector<std::string_view>(allowed),
                      "unknown key of " + context);
}

void refuse_unknown_keys(const json& obj, const std::string& where,
                         const std::vector<std::string_view>& allowed, const std::string& reason) {
  for (const auto& item : obj.items()) {
    if (std::find(allowed.begin(), allowed.end(), item.key()) != allowed.end()) continue;
    std::string known;
    for (auto k : allowed) known += (known.empty() ? "" : ", ") + std::string(k);
    throw InvalidArgument(key_path(where, item.key()), reason + " (known: " + known + ")");
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
  if (is_sparse_matrix_json(j)) return MatrixX(sparse_matrix_from_json(j, key));
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

bool is_sparse_matrix_json(const json& j) {
  return j.is_object();
}

SparseMatrix sparse_matrix_from_json(const json& j, const std::string& key) {
  if (!is_sparse_matrix_json(j)) return MatrixX(matrix_from_json(j, key)).sparseView(0.0, 0.0);
  check_keys(j, key, {"rows", "cols", "triplets"}, "a sparse matrix");
  auto size = [&](std::string_view name) {
    const std::string k = key_path(key, name);
    const double v = number_from_json(required_key(j, key, name), k);
    if (!(v >= 0 && v <= 1e8 && v == std::floor(v)))
      throw InvalidArgument(
          k, "must be a whole number in [0, 1e8], got " + fremond::detail::format_number(v));
    return static_cast<int>(v);
  };
  const int rows = size("rows"), cols = size("cols");
  const json& list = required_key(j, key, "triplets");
  const std::string list_key = key_path(key, "triplets");
  if (!list.is_array())
    throw InvalidArgument(list_key, "must be a list of [i, j, value], got " + describe_json(list));
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(list.size());
  for (std::size_t t = 0; t < list.size(); ++t) {
    const std::string k = index_path(list_key, t);
    const json& e = list[t];
    if (!e.is_array() || e.size() != 3)
      throw InvalidArgument(k, "must be [i, j, value], got " + describe_json(e));
    int at[2];
    for (std::size_t d = 0; d < 2; ++d) {
      const double v = number_from_json(e[d], index_path(k, d));
      const int limit = d == 0 ? rows : cols;
      if (!(v >= 0 && v < limit && v == std::floor(v)))
        throw InvalidArgument(index_path(k, d), std::string(d == 0 ? "a row" : "a column") +
                                                    " index must be a whole number in [0, " +
                                                    std::to_string(limit) + "), got " +
                                                    fremond::detail::format_number(v));
      at[d] = static_cast<int>(v);
    }
    entries.emplace_back(at[0], at[1], number_from_json(e[2], index_path(k, 2)));
  }
  // Each entry once: a repeated (i, j) is refused, not summed.
  std::vector<std::size_t> order(entries.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto place = [&](std::size_t t) { return std::pair(entries[t].col(), entries[t].row()); };
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return place(a) < place(b); });
  for (std::size_t k = 1; k < order.size(); ++k)
    if (place(order[k]) == place(order[k - 1]))
      throw InvalidArgument(index_path(list_key, order[k]),
                            "the entry (" + std::to_string(entries[order[k]].row()) + ", " +
                                std::to_string(entries[order[k]].col()) + ") is also " +
                                index_path("triplets", order[k - 1]));
  SparseMatrix A(rows, cols);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

}  // namespace fremond::io::detail
