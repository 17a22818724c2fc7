#pragma once
// Private to the library: reading JSON documents with messages that name the key as the file spells
// it (`M[1][2]`, `law.normal.p`, `law.e[1]`) and the reason. Typed readers, required and unknown
// keys, and a parser that names the key where the text stops being JSON. Every function refuses
// what it cannot use with InvalidArgument; nothing is filled in silently, and nothing here prints.
#include <cstddef>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "fremond/core/types.hpp"
#include "fremond/sparse/sparse_problem.hpp"

namespace fremond::io::detail {

using json = nlohmann::json;

/// `where.key`, or `key` when `where` is empty (the top level of a file).
std::string key_path(const std::string& where, std::string_view key);
/// `where[i]`.
std::string index_path(const std::string& where, std::size_t i);
/// A short description of a JSON value for messages: `a string "abc"`, `null`, `an array`, ...
std::string describe_json(const json& j);

/// Parses one JSON document. Refuses, naming the key being read where there is one: empty input,
/// text that is not JSON (with line and column), a number too large for a double (standard JSON has
/// no NaN or infinity, but `1e999` overflows), and a key given twice in one object (the parser
/// would otherwise keep one of them silently). `root` names the whole document in messages that
/// have no key (e.g. "problem").
json parse_json(std::string_view text, const std::string& root);

/// Throws unless `j` is an object; `where` names it.
void require_object(const json& j, const std::string& where);
/// Refuses any key of `obj` not in `allowed`: "where.key: unknown key of <context> (known: ...)".
void check_keys(const json& obj, const std::string& where,
                std::initializer_list<std::string_view> allowed, const std::string& context);
/// The same with a list built at run time and the whole reason: "where.key: <reason> (known: ...)".
void refuse_unknown_keys(const json& obj, const std::string& where,
                         const std::vector<std::string_view>& allowed, const std::string& reason);
/// obj[key], or "where.key: missing (required)" when absent.
const json& required_key(const json& obj, const std::string& where, std::string_view key);
/// &obj[key], or nullptr when absent.
const json* optional_key(const json& obj, std::string_view key);

/// A string, or "key: must be a string, got ...".
std::string string_from_json(const json& j, const std::string& key);
/// A finite number (booleans and null are not numbers), or an error naming `key`.
double number_from_json(const json& j, const std::string& key);
/// A number or a non-empty list of numbers (elements named `key[i]`). With contacts ≥ 0 a list must
/// have one value or one per contact.
std::vector<double> number_or_list(const json& j, const std::string& key, int contacts = -1);
/// A list of finite numbers.
VectorX vector_from_json(const json& j, const std::string& key);
/// A list of rows, each a list of finite numbers, all of one length (docs/problem-file.md: matrices
/// are lists of rows). `[]` is the 0×0 matrix; `[[], []]` is 2×0. Or the sparse form of
/// sparse_matrix_from_json, made dense.
MatrixX matrix_from_json(const json& j, const std::string& key);
/// True when `j` is a matrix in the sparse form (an object; docs/problem-file.md).
bool is_sparse_matrix_json(const json& j);
/// `{"rows": m, "cols": n, "triplets": [[i, j, value], ...]}` (0-based, each (i, j) at most once,
/// entries not listed zero), or a list of rows as matrix_from_json reads it. Keys named
/// `key.rows`, `key.triplets[3][1]`, ...
SparseMatrix sparse_matrix_from_json(const json& j, const std::string& key);

}  // namespace fremond::io::detail
