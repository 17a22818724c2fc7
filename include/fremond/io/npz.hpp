#pragma once
/// @file NumPy's .npy and .npz files, written without a library: an .npz is a zip archive of .npy
/// files, here stored uncompressed (numpy.load reads it as it reads np.savez's).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fremond::io {

/// One array: its name in the archive (without .npy), NumPy's type descriptor (`<f8`, `|u1`,
/// `|i1`, `<i4`, `<U12`), its shape (empty: a scalar) and its bytes in C order.
struct NpyArray {
  std::string name;
  std::string descr;
  std::vector<std::size_t> shape;
  std::string bytes;
};

/// Arrays of doubles, bytes, signed bytes and 32-bit integers in the host's byte order, and of
/// strings as NumPy's fixed-width unicode (`<U`n, n the longest). Throws InvalidArgument naming
/// `name` when the shape's product is not the number of values.
NpyArray npy_array(const std::string& name, const std::vector<double>& values,
                   std::vector<std::size_t> shape);
NpyArray npy_array(const std::string& name, const std::vector<std::uint8_t>& values,
                   std::vector<std::size_t> shape);
NpyArray npy_array(const std::string& name, const std::vector<std::int8_t>& values,
                   std::vector<std::size_t> shape);
NpyArray npy_array(const std::string& name, const std::vector<std::int32_t>& values,
                   std::vector<std::size_t> shape);
NpyArray npy_array(const std::string& name, const std::vector<std::string>& values,
                   std::vector<std::size_t> shape);

/// One .npy file (format 1.0, its header padded to 64 bytes).
std::string npy_file(const NpyArray& array);

/// The .npz archive of `arrays` (names unique): a zip of name.npy files, stored, each with its
/// CRC-32. Throws InvalidArgument("npz", ...) for a duplicate name, or an archive beyond what a
/// zip without its 64-bit extension holds (4 GiB, 65535 files).
std::string npz_archive(const std::vector<NpyArray>& arrays);

/// The CRC-32 of zip files (IEEE 802.3, reflected, polynomial 0xEDB88320).
std::uint32_t crc32(const std::string& bytes);

}  // namespace fremond::io
