// NumPy's .npy and .npz files (see npz.hpp): NEP 1's .npy format 1.0, and a stored zip archive
// (PKWARE's APPNOTE: local headers, the central directory and its end record).
#include "fremond/io/npz.hpp"

#include <array>
#include <bit>
#include <cstring>
#include <limits>
#include <set>

#include "fremond/core/error.hpp"

namespace fremond::io {

namespace {

// The host's byte order in a NumPy descriptor; zip's own numbers are always little-endian.
constexpr char kOrder = std::endian::native == std::endian::little ? '<' : '>';

std::size_t product(const std::vector<std::size_t>& shape) {
  std::size_t n = 1;
  for (std::size_t d : shape) n *= d;
  return n;
}

template <class T>
NpyArray raw(const std::string& name, const std::vector<T>& values, std::vector<std::size_t> shape,
             std::string descr) {
  if (product(shape) != values.size())
    throw InvalidArgument(name, "the shape holds " + std::to_string(product(shape)) +
                                    " values, the array " + std::to_string(values.size()));
  NpyArray a{name, std::move(descr), std::move(shape),
             std::string(values.size() * sizeof(T), '\0')};
  if (!values.empty()) std::memcpy(a.bytes.data(), values.data(), a.bytes.size());
  return a;
}

void put16(std::string& out, std::uint32_t v) {
  out += static_cast<char>(v & 0xff);
  out += static_cast<char>((v >> 8) & 0xff);
}
void put32(std::string& out, std::uint32_t v) {
  put16(out, v & 0xffff);
  put16(out, v >> 16);
}

constexpr std::array<std::uint32_t, 256> kCrcTable = [] {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t[i] = c;
  }
  return t;
}();

}  // namespace

std::uint32_t crc32(const std::string& bytes) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (const char ch : bytes) c = kCrcTable[(c ^ static_cast<unsigned char>(ch)) & 0xff] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

NpyArray npy_array(const std::string& name, const std::vector<double>& values,
                   std::vector<std::size_t> shape) {
  return raw(name, values, std::move(shape), std::string(1, kOrder) + "f8");
}
NpyArray npy_array(const std::string& name, const std::vector<std::uint8_t>& values,
                   std::vector<std::size_t> shape) {
  return raw(name, values, std::move(shape), "|u1");
}
NpyArray npy_array(const std::string& name, const std::vector<std::int8_t>& values,
                   std::vector<std::size_t> shape) {
  return raw(name, values, std::move(shape), "|i1");
}
NpyArray npy_array(const std::string& name, const std::vector<std::int32_t>& values,
                   std::vector<std::size_t> shape) {
  return raw(name, values, std::move(shape), std::string(1, kOrder) + "i4");
}

NpyArray npy_array(const std::string& name, const std::vector<std::string>& values,
                   std::vector<std::size_t> shape) {
  if (product(shape) != values.size())
    throw InvalidArgument(name, "the shape holds " + std::to_string(product(shape)) +
                                    " values, the array " + std::to_string(values.size()));
  // NumPy's `U` is UTF-32 in fixed width; the library's names are ASCII, one code unit each.
  std::size_t width = 1;
  for (const std::string& s : values) width = std::max(width, s.size());
  std::vector<std::uint32_t> units(values.size() * width, 0);
  for (std::size_t i = 0; i < values.size(); ++i)
    for (std::size_t k = 0; k < values[i].size(); ++k)
      units[i * width + k] = static_cast<unsigned char>(values[i][k]);
  NpyArray a =
      raw(name, units, {units.size()}, std::string(1, kOrder) + "U" + std::to_string(width));
  a.shape = std::move(shape);
  return a;
}

std::string npy_file(const NpyArray& a) {
  std::string dims;  // (2, 3), (2,) or ()
  for (std::size_t k = 0; k < a.shape.size(); ++k)
    dims += (k ? ", " : "") + std::to_string(a.shape[k]);
  if (a.shape.size() == 1) dims += ',';
  std::string header =
      "{'descr': '" + a.descr + "', 'fortran_order': False, 'shape': (" + dims + "), }";
  // Magic, version and length take 10 bytes; spaces and a newline end the header on 64 bytes.
  const std::size_t total = (10 + header.size() + 1 + 63) / 64 * 64;
  header.append(total - 10 - header.size() - 1, ' ');
  header += '\n';
  std::string out("\x93NUMPY\x01\x00", 8);
  put16(out, static_cast<std::uint32_t>(header.size()));
  return out + header + a.bytes;
}

std::string npz_archive(const std::vector<NpyArray>& arrays) {
  constexpr std::uint64_t kLimit = std::numeric_limits<std::uint32_t>::max();
  if (arrays.size() >= 0xffff)
    throw InvalidArgument("npz",
                          "holds at most 65534 arrays, got " + std::to_string(arrays.size()));
  std::set<std::string> names;
  std::string out, directory;
  for (const NpyArray& a : arrays) {
    if (!names.insert(a.name).second)
      throw InvalidArgument("npz", "the array name '" + a.name + "' is given twice");
    const std::string file = npy_file(a), name = a.name + ".npy";
    if (file.size() >= kLimit || out.size() + file.size() + name.size() + 30 >= kLimit)
      throw InvalidArgument("npz", "the archive would pass 4 GiB, beyond a zip without ZIP64");
    const std::uint32_t crc = crc32(file), size = static_cast<std::uint32_t>(file.size());
    const std::uint32_t offset = static_cast<std::uint32_t>(out.size());
    // The fields shared by the local header and the directory entry: version 2.0, no flags,
    // stored, the DOS date 1980-01-01 00:00 (a fixed date: the same atlas gives the same bytes).
    std::string common;
    put16(common, 20);
    put16(common, 0);
    put16(common, 0);
    put16(common, 0);
    put16(common, 0x21);
    put32(common, crc);
    put32(common, size);
    put32(common, size);
    put16(common, static_cast<std::uint32_t>(name.size()));
    put16(common, 0);
    put32(out, 0x04034b50);
    out += common + name + file;
    put32(directory, 0x02014b50);
    put16(directory, 20);  // made by: MS-DOS, version 2.0
    directory += common;
    put16(directory, 0);  // comment
    put16(directory, 0);  // disk
    put16(directory, 0);  // internal attributes
    put32(directory, 0);  // external attributes
    put32(directory, offset);
    directory += name;
  }
  if (out.size() + directory.size() >= kLimit)
    throw InvalidArgument("npz", "the archive would pass 4 GiB, beyond a zip without ZIP64");
  const auto start = static_cast<std::uint32_t>(out.size());
  out += directory;
  put32(out, 0x06054b50);
  put16(out, 0);
  put16(out, 0);
  put16(out, static_cast<std::uint32_t>(arrays.size()));
  put16(out, static_cast<std::uint32_t>(arrays.size()));
  put32(out, static_cast<std::uint32_t>(directory.size()));
  put32(out, start);
  put16(out, 0);
  return out;
}

}  // namespace fremond::io
