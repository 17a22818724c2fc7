// Siconos's 2-D friction-contact files (docs/sparse.md): a line reader over the layout its
// numerics library writes (dimension, contacts, matrices as NumericsMatrix prints them, vectors).
#include "fremond/io/siconos_file.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/detail/validate.hpp"
#include "fremond/core/error.hpp"
#include "sparse/detail/mass_inverse.hpp"

namespace fremond::io {

namespace {

class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}

  // The next line that is not blank; refuses the end of the file, saying what was expected.
  std::string_view next(const std::string& expected) {
    while (pos_ < text_.size()) {
      const auto end = text_.find('\n', pos_);
      const auto stop = end == std::string_view::npos ? text_.size() : end;
      std::string_view line = text_.substr(pos_, stop - pos_);
      pos_ = stop + 1;
      ++number_;
      if (line.find_first_not_of(" \t\r") != std::string_view::npos) return line;
    }
    throw InvalidArgument("line " + std::to_string(number_),
                          "the file ends where " + expected + " was expected");
  }
  // The next non-blank line without consuming it ("" at the end).
  std::string_view peek() {
    const auto saved = pos_;
    const int line = number_;
    std::string_view out;
    try {
      out = next("");
    } catch (const InvalidArgument&) {
    }
    pos_ = saved;
    number_ = line;
    return out;
  }
  bool at_end() { return peek().empty(); }
  [[noreturn]] void fail(const std::string& reason) const {
    throw InvalidArgument("line " + std::to_string(number_), reason);
  }
  // Out of line: GCC 12 misreads the string concatenation inlined into the number loop
  // (-Wrestrict).
  [[noreturn, gnu::noinline, gnu::cold]] void refuse_token(std::string_view token,
                                                           const char* why) const {
    std::string text = "'";
    text.append(token).append("' ").append(why);
    fail(text);
  }

  // The whitespace-separated numbers of a line; `values`: the data's numbers, whose significant
  // digits are counted (take_digits).
  std::vector<double> numbers(std::string_view line, bool values = false) {
    std::vector<double> out;
    std::size_t i = 0;
    while (true) {
      i = line.find_first_not_of(" \t\r", i);
      if (i == std::string_view::npos) break;
      auto j = line.find_first_of(" \t\r", i);
      if (j == std::string_view::npos) j = line.size();
      out.push_back(number(line.substr(i, j - i)));
      if (values) digits_ = std::max(digits_, significant_digits(line.substr(i, j - i)));
      i = j;
    }
    return out;
  }
  double number(std::string_view token) const {
    const auto first_char = token.find_first_not_of(" \t\r");
    token = first_char == std::string_view::npos ? std::string_view{} : token.substr(first_char);
    token = token.substr(0, token.find_last_not_of(" \t\r") + 1);
    double v = 0.0;
    const auto* first = token.data() + (token.size() > 1 && token[0] == '+' ? 1 : 0);
    const auto [end, ec] = std::from_chars(first, token.data() + token.size(), v);
    if (ec != std::errc() || end != token.data() + token.size())
      refuse_token(token, "is not a number");
    if (!std::isfinite(v)) refuse_token(token, "is not finite");
    return v;
  }
  int integer(std::string_view token, long long lo, long long hi, const std::string& what) const {
    if (token.find_first_not_of(" \t\r") == std::string_view::npos) fail(what + " is missing");
    const double v = number(token);
    if (!(v == std::floor(v)) || v < static_cast<double>(lo) || v > static_cast<double>(hi))
      fail(what + " must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
           "], got '" + std::string(token) + "'");
    return static_cast<int>(v);
  }
  // The most significant digits of a value read since the last call (0: none read).
  int take_digits() { return std::exchange(digits_, 0); }
  // A line holding one integer.
  int integer_line(long long lo, long long hi, const std::string& what) {
    const std::string_view line = next(what);
    const auto v = numbers(line);
    if (v.size() != 1) fail(what + " must stand alone on its line");
    return integer(line, lo, hi, what);
  }
  // `count` numbers, over as many lines as they take (kept as read: the file proves the count).
  Eigen::VectorXd vector(int count, const std::string& what) {
    std::vector<double> out;
    out.reserve(static_cast<std::size_t>(std::min(count, 1 << 16)));
    while (static_cast<int>(out.size()) < count) {
      const auto v = numbers(next(what), true);
      if (out.size() + v.size() > static_cast<std::size_t>(count))
        fail(what + " must have " + std::to_string(count) + " numbers, got more");
      out.insert(out.end(), v.begin(), v.end());
    }
    return Eigen::Map<const Eigen::VectorXd>(out.data(), count);
  }

 private:
  // The digits of a number's mantissa from its first non-zero one: "-0.000113414" 6, "2.0" 2.
  static int significant_digits(std::string_view token) {
    int count = 0;
    bool started = false;
    for (const char ch : token) {
      if (ch == 'e' || ch == 'E') break;
      if (ch < '0' || ch > '9') continue;
      started = started || ch != '0';
      if (started) ++count;
    }
    return count;
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  int number_ = 0;
  int digits_ = 0;
};

// How well numbers printed with at most `digits` significant digits are known, relative to each:
// half a unit of the last digit, at most 5·10^-digits. Fewer than 6 (printf's %g) are taken as
// written by hand, exact.
double printed_rounding(int digits) {
  if (digits < 6) return 0.0;
  const std::string text = "5e-" + std::to_string(digits);  // the decimal, correctly rounded
  double v = 0.0;
  std::from_chars(text.data(), text.data() + text.size(), v);
  return v;
}

// Rows, columns, non-zeros: far beyond any planar problem file (Siconos's largest: 14,004 rows).
constexpr long long kLargest = 10000000;

// A matrix as NumericsMatrix writes it: storage type, rows, columns, then column-major values
// (dense) or a CSparse print (sparse), after the origin of the sparse storage.
SparseMatrix matrix(Lines& in, const std::string& what) {
  const int storage = in.integer_line(0, 3, what + "'s storage type");
  if (storage != 0 && storage != 2)
    in.fail(what + ": storage type " + std::to_string(storage) +
            " is not read (0 dense and 2 sparse are); have Siconos write the problem with one of "
            "those");
  const int rows = in.integer_line(1, kLargest, what + "'s row count");
  const int cols = in.integer_line(1, kLargest, what + "'s column count");
  std::vector<Eigen::Triplet<double>> entries;
  if (storage == 0) {
    if (static_cast<long long>(rows) * cols > kLargest)
      in.fail(what + " is " + std::to_string(rows) + "x" + std::to_string(cols) +
              ": too large for dense storage (at most " + std::to_string(kLargest) +
              " entries); store it sparse (type 2)");
    const Eigen::VectorXd v = in.vector(rows * cols, what + "'s values");
    for (int j = 0; j < cols; ++j)
      for (int i = 0; i < rows; ++i)
        if (v(j * rows + i) != 0.0) entries.emplace_back(i, j, v(j * rows + i));
  } else {
    in.integer_line(0, 3, what + "'s sparse origin");
    std::string_view header = in.next(what + "'s CSparse header");
    if (header.find("CSparse") != std::string_view::npos) header = in.next(what + "'s size line");
    const bool triplet = header.find("triplet:") != std::string_view::npos;
    const auto by = header.find("-by-");
    const auto nnz_at = header.find("nnz:");
    if (by == std::string_view::npos || nnz_at == std::string_view::npos)
      in.fail(what + ": expected a CSparse size line 'm-by-n, nzmax: ... nnz: ...'");
    // header[begin, end), clamped: a malformed line gives an empty field, which integer() refuses.
    auto field = [&header](std::size_t begin, std::size_t end) {
      begin = std::min(begin, header.size());
      end = std::clamp(end, begin, header.size());
      return header.substr(begin, end - begin);
    };
    const std::size_t start = triplet ? header.find("triplet:") + 8 : 0;
    const int m = in.integer(field(start, by), 1, kLargest, what + "'s rows");
    const int n = in.integer(field(by + 4, header.find(',', by)), 1, kLargest, what + "'s columns");
    const int nnz = in.integer(field(nnz_at + 4, header.find(',', nnz_at)), 0, kLargest,
                               what + "'s non-zero count");
    if (m != rows || n != cols)
      in.fail(what + " is declared " + std::to_string(rows) + "x" + std::to_string(cols) +
              " but stored " + std::to_string(m) + "x" + std::to_string(n));
    entries.reserve(static_cast<std::size_t>(std::min(nnz, 1 << 16)));  // the file proves the rest
    int column = -1;
    while (static_cast<int>(entries.size()) < nnz) {
      const std::string_view line = in.next(what + "'s entries");
      const auto colon = line.find(':');
      if (colon == std::string_view::npos) in.fail(what + ": expected an entry 'i : value'");
      const std::string_view left = line.substr(0, colon);
      if (!triplet && left.find("col") != std::string_view::npos) {
        const auto at = left.find("col") + 3;
        column = in.integer(left.substr(at), 0, n - 1, what + "'s column");
        continue;
      }
      const auto idx = in.numbers(left);
      const auto val = in.numbers(line.substr(colon + 1), true);
      if (val.size() != 1 || idx.size() != (triplet ? 2u : 1u) || (!triplet && column < 0))
        in.fail(what + ": expected an entry '" + std::string(triplet ? "i j" : "i") + " : value'");
      const double i = idx[0], j = triplet ? idx[1] : column;
      if (!(i == std::floor(i) && i >= 0 && i < m && j == std::floor(j) && j >= 0 && j < n))
        in.fail(what + ": entry index out of the " + std::to_string(m) + "x" + std::to_string(n) +
                " matrix");
      entries.emplace_back(static_cast<int>(i), static_cast<int>(j), val[0]);
    }
    // Empty columns after the last entry still print their header.
    while (!triplet && in.peek().find("col") != std::string_view::npos) in.next("");
  }
  SparseMatrix A(rows, cols);
  A.setFromTriplets(entries.begin(), entries.end());  // duplicates add, as in CSparse
  return A;
}

// One row of a NumericsMatrix print stands alone; a vector's line holds several numbers.
bool next_is_matrix(Lines& in) {
  const std::string_view line = in.peek();
  return !line.empty() && in.numbers(line).size() == 1;
}

// The columns 2i, 2i + 1 of H as W_N, W_T.
void split_jacobian(const SparseMatrix& H, SparseImpactProblem& pb) {
  const int c = static_cast<int>(H.cols() / 2);
  std::vector<Eigen::Triplet<double>> N, T;
  for (int j = 0; j < H.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(H, j); it; ++it)
      (j % 2 == 0 ? N : T).emplace_back(static_cast<int>(it.row()), j / 2, it.value());
  pb.W_N.resize(H.rows(), c);
  pb.W_T.resize(H.rows(), c);
  pb.W_N.setFromTriplets(N.begin(), N.end());
  pb.W_T.setFromTriplets(T.begin(), T.end());
}

}  // namespace

ImpactLaw SiconosProblem::law() const {
  return ImpactLaw::newton_coulomb(0.0, PerContact(mu));
}

bool looks_like_siconos_file(std::string_view text) {
  // The dimension on the first line, the number of contacts on the second: a JSON document
  // holding a bare number has no second line.
  std::string_view line[2];
  std::size_t pos = 0;
  for (auto& l : line) {
    while (true) {
      if (pos >= text.size()) return false;
      const auto end = std::min(text.find('\n', pos), text.size());
      l = text.substr(pos, end - pos);
      pos = end + 1;
      const auto a = l.find_first_not_of(" \t\r");
      if (a == std::string_view::npos) continue;
      l = l.substr(a, l.find_last_not_of(" \t\r") + 1 - a);
      break;
    }
  }
  return (line[0] == "2" || line[0] == "3") && !line[1].empty() &&
         line[1].find_first_not_of("0123456789") == std::string_view::npos;
}

SiconosProblem parse_siconos_file(std::string_view text) {
  Lines in(text);
  const int dimension = in.integer_line(2, 3, "the dimension");
  if (dimension != 2)
    in.fail(
        "the dimension must be 2 (a planar problem: one normal and one tangential row a "
        "contact), got 3");
  const int c = in.integer_line(1, kLargest / 2, "the number of contacts");
  const int rows = 2 * c;
  SiconosProblem out;
  const SparseMatrix first = matrix(in, "the first matrix");
  // The digits each number of the local form's G and q is printed with (Siconos's own files:
  // G's sparse print 6 significant digits, q 25).
  const int first_digits = in.take_digits();
  if (next_is_matrix(in)) {
    out.form = SiconosProblem::Form::global;
    const int n = static_cast<int>(first.rows());
    if (first.cols() != n)
      in.fail("M must be square, got " + std::to_string(n) + "x" + std::to_string(first.cols()));
    const SparseMatrix H = matrix(in, "H");
    if (H.rows() != n || H.cols() != rows)
      in.fail("H must be " + std::to_string(n) + "x" + std::to_string(rows) +
              " (dofs x two rows a contact), got " + std::to_string(H.rows()) + "x" +
              std::to_string(H.cols()));
    const Eigen::VectorXd q = in.vector(n, "q");
    const Eigen::VectorXd b = in.vector(rows, "b");
    out.impact.M = first;
    split_jacobian(H, out.impact);
    out.impact.w_N = b(Eigen::seq(0, rows - 1, 2));
    out.impact.w_T = b(Eigen::seq(1, rows - 1, 2));
    out.impact.qdot_A = Eigen::VectorXd::Zero(n);
    validate(out.impact);  // M positive definite before it is used
    const SparseMatrix qs = q.sparseView(0.0, 0.0);
    out.impact.qdot_A = SparseMatrix(detail::solve_mass(out.impact.M, qs)).toDense();
  } else {
    if (first.rows() != rows || first.cols() != rows)
      in.fail("the Delassus matrix W must be " + std::to_string(rows) + "x" + std::to_string(rows) +
              " (two rows a contact), got " + std::to_string(first.rows()) + "x" +
              std::to_string(first.cols()));
    out.contact.G = first;
    out.contact.G_rounding = printed_rounding(first_digits);
    out.contact.D_A = in.vector(rows, "q");
    out.contact.D_A_rounding = printed_rounding(in.take_digits());
    out.contact.tangential = true;
  }
  const Eigen::VectorXd mu = in.vector(c, "mu");
  if (!in.at_end()) {
    in.next("");
    in.fail("unexpected text after the last friction coefficient");
  }
  out.mu.assign(mu.data(), mu.data() + c);
  for (int i = 0; i < c; ++i)
    if (!(out.mu[static_cast<std::size_t>(i)] >= 0.0))
      throw InvalidArgument("mu[" + std::to_string(i) + "]",
                            "must be >= 0, got " + detail::format_number(mu(i)));
  if (out.form == SiconosProblem::Form::local) validate(out.contact);
  return out;
}

}  // namespace fremond::io
