// The .npy/.npz writer against the formats' own fixed points: the CRC-32 check value of
// "123456789", a .npy header padded to 64 bytes and ended by a newline, and a zip whose end record
// points at its central directory. numpy.load reading it back is tests/python/test_atlas.py's.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "fremond/core/error.hpp"
#include "fremond/io/npz.hpp"

namespace fremond::io {
namespace {

std::uint32_t le32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (int k = 3; k >= 0; --k) v = (v << 8) | static_cast<unsigned char>(s[at + k]);
  return v;
}

TEST(Npz, Crc32CheckValue) {
  // The check value of CRC-32/ISO-HDLC, the zip format's CRC.
  EXPECT_EQ(crc32("123456789"), 0xCBF43926u);
  EXPECT_EQ(crc32(""), 0u);
}

TEST(Npz, NpyHeaderIsPaddedAndDescribesTheArray) {
  const std::string f = npy_file(npy_array("x", std::vector<double>{1, 2, 3, 4, 5, 6}, {2, 3}));
  ASSERT_EQ(f.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  const std::size_t header =
      static_cast<unsigned char>(f[8]) + 256u * static_cast<unsigned char>(f[9]);
  EXPECT_EQ((10 + header) % 64, 0u);
  EXPECT_EQ(f[10 + header - 1], '\n');
  EXPECT_NE(f.find("'shape': (2, 3)"), std::string::npos);
  EXPECT_NE(f.find("'fortran_order': False"), std::string::npos);
  EXPECT_EQ(f.size(), 10 + header + 6 * sizeof(double));
  EXPECT_NE(npy_file(npy_array("s", std::vector<double>{7}, {})).find("'shape': ()"),
            std::string::npos);
  EXPECT_NE(npy_file(npy_array("v", std::vector<std::int8_t>{1, 2}, {2})).find("'shape': (2,)"),
            std::string::npos);
  const std::string u = npy_file(npy_array("u", std::vector<std::string>{"ab", "cde"}, {2}));
  EXPECT_NE(u.find("U3'"), std::string::npos);
}

TEST(Npz, ArchiveEndsOnItsDirectory) {
  const std::string z = npz_archive({npy_array("a", std::vector<double>{1.5}, {1}),
                                     npy_array("b", std::vector<std::uint8_t>{1, 2, 3}, {3})});
  ASSERT_GE(z.size(), 22u);
  const std::size_t end = z.size() - 22;
  EXPECT_EQ(le32(z, end), 0x06054b50u);
  const std::uint32_t size = le32(z, end + 12), start = le32(z, end + 16);
  EXPECT_EQ(start + size, end);
  EXPECT_EQ(le32(z, start), 0x02014b50u);
  EXPECT_EQ(le32(z, 0), 0x04034b50u);
  // The first file's CRC is the .npy's.
  EXPECT_EQ(le32(z, 14), crc32(npy_file(npy_array("a", std::vector<double>{1.5}, {1}))));
}

TEST(Npz, RefusesWhatItCannotWrite) {
  EXPECT_THROW(npy_array("x", std::vector<double>{1, 2}, {3}), InvalidArgument);
  EXPECT_THROW(npz_archive({npy_array("a", std::vector<double>{1}, {1}),
                            npy_array("a", std::vector<double>{2}, {1})}),
               InvalidArgument);
}

}  // namespace
}  // namespace fremond::io
