// IB2d structure files (io::read_ib2d_structure, io::write_ib2d_structure): a bit-for-bit round
// trip through every file kind, the optional alpha column, absent optional files, and errors that
// name the file, the line and what was expected.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>

#include "jellysim/core/errors.hpp"
#include "jellysim/io/ib2d_files.hpp"
#include "jellysim/jellyfish/hoover_miller.hpp"

namespace jellysim::io {
namespace {

namespace fs = std::filesystem;
using elastic::Ib2dStructure;

/// A fresh directory under the system's temporary directory, removed with the fixture.
class Ib2dFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device seed;
    dir_ = fs::temp_directory_path() / ("jellysim_ib2d_" + std::to_string(seed()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  fs::path stem() const { return dir_ / "jelly"; }
  fs::path file(const std::string& extension) const { return fs::path(stem().string() + extension); }
  void put(const std::string& extension, const std::string& text) const {
    std::ofstream out(file(extension), std::ios::binary);
    out << text;
  }
  /// Four vertices, for the files that refer to them.
  void put_vertices() const { put(".vertex", "4\n0 0\n1 0\n1 1\n0 1\n"); }
  /// The message of the InputError reading the structure throws ("" when it throws none).
  std::string read_error() const {
    try {
      read_ib2d_structure(stem());
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

void expect_same(const Ib2dStructure& a, const Ib2dStructure& b) {
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  for (std::size_t k = 0; k < a.vertices.size(); ++k) {
    EXPECT_EQ(bits(a.vertices[k].x), bits(b.vertices[k].x)) << k;
    EXPECT_EQ(bits(a.vertices[k].y), bits(b.vertices[k].y)) << k;
  }
  for (const auto& [p, q] : {std::pair{&a.springs, &b.springs}, std::pair{&a.damped_springs, &b.damped_springs}}) {
    ASSERT_EQ(p->size(), q->size());
    for (std::size_t k = 0; k < p->size(); ++k) {
      EXPECT_EQ((*p)[k].master, (*q)[k].master);
      EXPECT_EQ((*p)[k].slave, (*q)[k].slave);
      EXPECT_EQ(bits((*p)[k].stiffness), bits((*q)[k].stiffness));
      EXPECT_EQ(bits((*p)[k].rest_length), bits((*q)[k].rest_length));
      EXPECT_EQ(bits((*p)[k].degree), bits((*q)[k].degree));
      EXPECT_EQ(bits((*p)[k].damping), bits((*q)[k].damping));
    }
  }
  ASSERT_EQ(a.beams.size(), b.beams.size());
  for (std::size_t k = 0; k < a.beams.size(); ++k) {
    EXPECT_EQ(a.beams[k].left, b.beams[k].left);
    EXPECT_EQ(a.beams[k].middle, b.beams[k].middle);
    EXPECT_EQ(a.beams[k].right, b.beams[k].right);
    EXPECT_EQ(bits(a.beams[k].stiffness), bits(b.beams[k].stiffness));
    EXPECT_EQ(bits(a.beams[k].curvature), bits(b.beams[k].curvature));
  }
  ASSERT_EQ(a.non_invariant_beams.size(), b.non_invariant_beams.size());
  for (std::size_t k = 0; k < a.non_invariant_beams.size(); ++k) {
    const auto& p = a.non_invariant_beams[k];
    const auto& q = b.non_invariant_beams[k];
    EXPECT_EQ(p.left, q.left);
    EXPECT_EQ(p.middle, q.middle);
    EXPECT_EQ(p.right, q.right);
    EXPECT_EQ(bits(p.stiffness), bits(q.stiffness));
    EXPECT_EQ(bits(p.curvature.x), bits(q.curvature.x));
    EXPECT_EQ(bits(p.curvature.y), bits(q.curvature.y));
  }
  ASSERT_EQ(a.targets.size(), b.targets.size());
  for (std::size_t k = 0; k < a.targets.size(); ++k) {
    EXPECT_EQ(a.targets[k].point, b.targets[k].point);
    EXPECT_EQ(bits(a.targets[k].stiffness), bits(b.targets[k].stiffness));
  }
}

Ib2dStructure sample() {
  Ib2dStructure s;
  s.vertices = {{0.1, -0.2}, {1.0 / 3.0, 2.0e-300}, {-0.0, 6.5536e10}, {std::numeric_limits<double>::denorm_min(), 1.0},
                {-7.311e-04, std::nextafter(1.0, 2.0)}};
  s.springs = {{0, 1, 6.5536e10, 0.1 / 3.0, 1.0, 0.0}, {1, 2, 0.0, 0.0, 2.5, 0.0}, {3, 4, 1e-3, 0.7, 10.0, 0.0}};
  s.damped_springs = {{4, 0, 12.5, 0.25, 1.0, 0.003}, {2, 3, 1e5, 1.0 / 7.0, 1.0, 0.0}};
  s.beams = {{0, 1, 2, 2.5e7, -1.0 / 11.0}, {2, 3, 4, 0.0, 0.0}};
  s.non_invariant_beams = {{1, 2, 3, 1.0, {0.3, -0.7}}, {4, 3, 0, 9.75e3, {-0.0, 1e-17}}};
  s.targets = {{0, 1e6}, {4, 0.5}};
  return s;
}

TEST_F(Ib2dFiles, EveryFileKindRoundTripsBitForBit) {
  const Ib2dStructure s = sample();
  write_ib2d_structure(s, stem());
  for (const char* extension : {".vertex", ".spring", ".d_spring", ".beam", ".nonInv_beam", ".target"})
    EXPECT_TRUE(fs::is_regular_file(file(extension))) << extension;
  expect_same(read_ib2d_structure(stem()), s);
  // Indices are 1-based in the files; line 1 is the count.
  std::ifstream in(file(".target"));
  std::string count, id;
  in >> count >> id;
  EXPECT_EQ(count, "2");
  EXPECT_EQ(id, "1");
}

TEST_F(Ib2dFiles, RewritingWithFewerListsRemovesTheirStaleFiles) {
  write_ib2d_structure(sample(), stem());
  Ib2dStructure s;
  s.vertices = {{1.0, 2.0}, {3.0, 4.0}};
  s.springs = {{0, 1, 5.0, 1.0, 1.0, 0.0}};
  write_ib2d_structure(s, stem());
  EXPECT_FALSE(fs::exists(file(".beam")));
  EXPECT_FALSE(fs::exists(file(".target")));
  expect_same(read_ib2d_structure(stem()), s);
  // Plain springs are written without the alpha column when every alpha is 1.
  std::ifstream in(file(".spring"));
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  EXPECT_EQ(line, "1 2 5 1");
}

TEST_F(Ib2dFiles, TheFifthSpringColumnIsTheDegreeOfNonlinearity) {
  put_vertices();
  put(".spring", "3\n1 2 1.0 0.5\n2 3 6.5536e+10 -0 \n3 4 2 1\n");
  Ib2dStructure s = read_ib2d_structure(stem());
  ASSERT_EQ(s.springs.size(), 3u);
  EXPECT_EQ(s.springs[1].stiffness, 6.5536e10);
  EXPECT_EQ(s.springs[0].degree, 1.0);
  EXPECT_EQ(s.springs[0].damping, 0.0);

  put(".spring", "2\n1 2 1.0 0.5 3\r\n4 1 2 1 1.5\r\n\r\n\n");
  s = read_ib2d_structure(stem());
  ASSERT_EQ(s.springs.size(), 2u);
  EXPECT_EQ(s.springs[0].master, 0);
  EXPECT_EQ(s.springs[0].slave, 1);
  EXPECT_EQ(s.springs[0].degree, 3.0);
  EXPECT_EQ(s.springs[1].master, 3);
  EXPECT_EQ(s.springs[1].degree, 1.5);

  put(".spring", "1\n1 2 1.0 0.5 11\n");
  const std::string e = read_error();
  EXPECT_NE(e.find("line 2 column 5 (alpha)"), std::string::npos) << e;
  EXPECT_NE(e.find("[1, 10]"), std::string::npos) << e;
  put(".spring", "2\n1 2 1.0 0.5 2\n2 3 1 1\n");
  EXPECT_NE(read_error().find("line 3"), std::string::npos) << read_error();
}

TEST_F(Ib2dFiles, MissingOptionalFilesGiveEmptyLists) {
  put(".vertex", "2\n-7.311e-04 1\n2 3\n");
  const Ib2dStructure s = read_ib2d_structure(stem());
  ASSERT_EQ(s.vertices.size(), 2u);
  EXPECT_EQ(s.vertices[0].x, -7.311e-04);
  EXPECT_TRUE(s.springs.empty());
  EXPECT_TRUE(s.damped_springs.empty());
  EXPECT_TRUE(s.beams.empty());
  EXPECT_TRUE(s.non_invariant_beams.empty());
  EXPECT_TRUE(s.targets.empty());
}

TEST_F(Ib2dFiles, AnIndexOutOfRangeNamesTheFileTheLineAndTheRange) {
  put_vertices();
  put(".beam", "2\n1 2 3 1 0\n2 3 300 1 0\n");
  const std::string e = read_error();
  EXPECT_NE(e.find("jelly.beam"), std::string::npos) << e;
  EXPECT_NE(e.find("line 3"), std::string::npos) << e;
  EXPECT_NE(e.find("index 300 is out of range [1, 4]"), std::string::npos) << e;
  put(".beam", "1\n0 2 3 1 0\n");
  EXPECT_NE(read_error().find("index 0 is out of range [1, 4]"), std::string::npos) << read_error();
}

TEST_F(Ib2dFiles, TheCountMustMatchTheRows) {
  put(".vertex", "3\n0 0\n1 1\n");
  std::string e = read_error();
  EXPECT_NE(e.find("jelly.vertex"), std::string::npos) << e;
  EXPECT_NE(e.find("line 1 says 3 rows, the file has 2"), std::string::npos) << e;
  put(".vertex", "1\n0 0\n1 1\n");
  EXPECT_NE(read_error().find("line 1 says 1 rows, the file has 2"), std::string::npos) << read_error();
  put(".vertex", "2\n0 0\n\n1 1\n");
  EXPECT_NE(read_error().find("line 3: blank line"), std::string::npos) << read_error();
  put(".vertex", "2.0\n0 0\n1 1\n");
  EXPECT_NE(read_error().find("line 1: expected the row count"), std::string::npos) << read_error();
  put(".vertex", "-2\n");
  EXPECT_NE(read_error().find("line 1: expected the row count"), std::string::npos) << read_error();
  put(".vertex", "");
  EXPECT_NE(read_error().find("empty"), std::string::npos) << read_error();
  put(".vertex", "3000000\n");
  EXPECT_NE(read_error().find("above the limit of 2000000"), std::string::npos) << read_error();
  put(".vertex", "0\n");
  EXPECT_TRUE(read_ib2d_structure(stem()).vertices.empty());
}

TEST_F(Ib2dFiles, NonFiniteValuesAreRefused) {
  put(".vertex", "2\n0 0\n1 nan\n");
  std::string e = read_error();
  EXPECT_NE(e.find("line 3 column 2 (y)"), std::string::npos) << e;
  EXPECT_NE(e.find("not a finite number"), std::string::npos) << e;
  put(".vertex", "2\n0 0\n-inf 1\n");
  e = read_error();
  EXPECT_NE(e.find("line 3 column 1 (x)"), std::string::npos) << e;
  put(".vertex", "1\n1e999 0\n");
  EXPECT_NE(read_error().find("line 2 column 1"), std::string::npos) << read_error();
  put(".vertex", "1\n0,5 0\n");
  EXPECT_NE(read_error().find("expected a number, got \"0,5\""), std::string::npos) << read_error();
  put(".vertex", "1\n# 0\n");
  EXPECT_NE(read_error().find("line 2 column 1 (x)"), std::string::npos) << read_error();
}

TEST_F(Ib2dFiles, EveryRowNeedsTheFilesColumnCount) {
  put_vertices();
  put(".target", "2\n1 5\n2 5 7\n");
  std::string e = read_error();
  EXPECT_NE(e.find("jelly.target' line 3: expected 2 columns \"id k\", got 3"), std::string::npos) << e;
  fs::remove(file(".target"));
  put(".spring", "1\n1 2 3\n");
  e = read_error();
  EXPECT_NE(e.find("line 2: expected 4 or 5 columns \"master slave k RL [alpha]\", got 3"), std::string::npos) << e;
}

TEST_F(Ib2dFiles, IndicesMustBeIntegers) {
  put_vertices();
  put(".target", "1\n2.5 10\n");
  std::string e = read_error();
  EXPECT_NE(e.find("line 2 column 1 (id): expected an integer point index in [1, 4]"), std::string::npos) << e;
  put(".target", "1\n3.0 10\n");  // an integer written as a float (IB2d's MATLAB reads it so)
  EXPECT_EQ(read_ib2d_structure(stem()).targets.at(0).point, 2);
}

TEST_F(Ib2dFiles, ValuesOutsideTheirRangesAreRefused) {
  put_vertices();
  put(".spring", "1\n2 2 1 1\n");
  EXPECT_NE(read_error().find("distinct points, got 2, 2"), std::string::npos) << read_error();
  put(".spring", "1\n1 2 -1 1\n");
  EXPECT_NE(read_error().find("column 3 (k): must be >= 0"), std::string::npos) << read_error();
  put(".spring", "1\n1 2 1 -0.5\n");
  EXPECT_NE(read_error().find("column 4 (RL): must be >= 0"), std::string::npos) << read_error();
  fs::remove(file(".spring"));
  put(".d_spring", "1\n1 2 1 1 -3\n");
  EXPECT_NE(read_error().find("column 5 (b): must be >= 0"), std::string::npos) << read_error();
  fs::remove(file(".d_spring"));
  put(".nonInv_beam", "1\n1 2 1 1 0 0\n");
  EXPECT_NE(read_error().find("distinct points"), std::string::npos) << read_error();
}

TEST_F(Ib2dFiles, ADirectoryIsNotAFile) {
  put_vertices();
  fs::create_directory(file(".spring"));
  const std::string e = read_error();
  EXPECT_NE(e.find("jelly.spring' is not a regular file: it is a directory"), std::string::npos) << e;
}

TEST_F(Ib2dFiles, TheVertexFileIsRequired) {
  put(".spring", "0\n");
  const std::string e = read_error();
  EXPECT_NE(e.find("jelly.vertex' cannot be read: no such file"), std::string::npos) << e;
}

TEST_F(Ib2dFiles, ADeviceIsNotAFile) {
  if (!fs::exists("/dev/zero")) GTEST_SKIP() << "no /dev/zero";
  fs::create_symlink("/dev/zero", file(".vertex"));
  EXPECT_NE(read_error().find("not a regular file: it is a character device"), std::string::npos) << read_error();
}

TEST_F(Ib2dFiles, AStructureTheReaderWouldRefuseIsNotWritten) {
  Ib2dStructure s;
  s.vertices = {{0.0, 0.0}, {1.0, 0.0}};
  s.springs = {{0, 2, 1.0, 1.0, 1.0, 0.0}};
  EXPECT_THROW(write_ib2d_structure(s, stem()), InputError);
  s.springs = {{0, 1, 1.0, 1.0, 1.0, 0.5}};  // damping has no column in a .spring file
  EXPECT_THROW(write_ib2d_structure(s, stem()), InputError);
  s.springs = {{0, 1, std::nan(""), 1.0, 1.0, 0.0}};
  EXPECT_THROW(write_ib2d_structure(s, stem()), InputError);
  EXPECT_FALSE(fs::exists(file(".vertex")));
  EXPECT_FALSE(fs::exists(file(".spring")));
}

// Our generated files read back through the importer to the same structure, bit for bit, and the
// shipped scenes/hoover-miller/jelly256.* are the generator's output.
TEST(HooverMiller, GeneratedFilesRoundTripThroughTheImporter) {
  const jellyfish::HooverMillerBell bell = jellyfish::hoover_miller_bell({});
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "jellysim_test_hoover_miller";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  io::write_ib2d_structure(bell.structure, dir / "jelly256");
  for (const std::filesystem::path& stem :
       {dir / "jelly256", std::filesystem::path(JELLYSIM_SOURCE_DIR) / "scenes/hoover-miller/jelly256"}) {
    const elastic::Ib2dStructure back = io::read_ib2d_structure(stem);
    ASSERT_EQ(back.vertices, bell.structure.vertices) << stem;
    ASSERT_EQ(back.springs.size(), bell.structure.springs.size());
    for (std::size_t k = 0; k < back.springs.size(); ++k) {
      EXPECT_EQ(back.springs[k].master, bell.structure.springs[k].master);
      EXPECT_EQ(back.springs[k].slave, bell.structure.springs[k].slave);
      EXPECT_EQ(back.springs[k].stiffness, bell.structure.springs[k].stiffness);
      EXPECT_EQ(back.springs[k].rest_length, bell.structure.springs[k].rest_length);
    }
    ASSERT_EQ(back.non_invariant_beams.size(), bell.structure.non_invariant_beams.size());
    for (std::size_t k = 0; k < back.non_invariant_beams.size(); ++k)
      EXPECT_EQ(back.non_invariant_beams[k].curvature, bell.structure.non_invariant_beams[k].curvature);
    ASSERT_EQ(back.targets.size(), bell.structure.targets.size());
    EXPECT_EQ(back.targets.back().point, bell.structure.targets.back().point);
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace jellysim::io
