#pragma once
// Private to the library: JSON → library types, shared by the impact-problem reader
// (docs/problem-file.md) and the scene reader. Every function refuses what it cannot use with
// InvalidArgument naming the key as the file spells it (`M[1][2]`, `law.normal.p`, `law.e[1]`) and
// the reason; nothing is filled in silently, and no function here prints.
#include <cstddef>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "fremond/core/types.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/potentials/registry.hpp"

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
/// are lists of rows). `[]` is the 0×0 matrix; `[[], []]` is 2×0.
MatrixX matrix_from_json(const json& j, const std::string& key);

/// An impact law from its JSON object (docs/problem-file.md, `law`): `type` is one of newton,
/// poisson, newton_coulomb, poisson_coulomb, fremond; e and mu are a number or one per contact; a
/// Frémond law names its potentials by their registry name ("normal", optional "tangential", which
/// may also be {"potential": "coulomb", "mu": ...}), every parameter a number or one per contact.
/// Keys a law type does not use are refused. Messages are prefixed by `where` (e.g. "law", so
/// `law.normal.p: must be > 1, got 0.5`). The law is validated for `contacts` contacts.
ImpactLaw law_from_json(const json& j, int contacts, const PotentialRegistry& registry,
                        const std::string& where);

}  // namespace fremond::io::detail
