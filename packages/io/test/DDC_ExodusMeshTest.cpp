// Exodus II mesh input checked before it is used (doc/user-guide.md,
// "Checks of a mesh file"): a classic netCDF file written by the Exodus II
// library holds exactly the data its header declares
// (netcdfClassicExtent() = its size); the same file cut short in its data or
// in its header, or with a header that declares 300 million nodes, is
// refused as truncated naming the file; a coordinate of 1e300 or NaN names
// the node and the coordinate limit.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Teuchos_DefaultComm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "DDC_ExodusMesh.hpp"
#include "DDC_ExodusWriter.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_NetcdfClassicExtent.hpp"
#include "DDC_TestErrors.hpp"

namespace fs = std::filesystem;

namespace {

using ddc::test::inputErrorOf;

class ExodusMeshInput : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ddc_io_exodus_mesh_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// A 3 x 2 Quad4 block written by the Exodus II library; node 0 at x = x0.
  std::string write(const std::string& name, double x0 = 0.0) {
    ddc::Mesh m;
    Teuchos::ParameterList r;
    r.set("Elements X", 3);
    r.set("Elements Y", 2);
    ddc::generateRectangle(m, "Block", ddc::CellType::Quad4, r, "Rectangle");
    m.coord(0)[0] = x0;
    const std::string path = (dir_ / name).string();
    ddc::ExodusWriter(Teuchos::DefaultComm<int>::getComm(), path, m, ddc::ExodusVariables());
    return path;
  }
  /// The first `bytes` bytes of `from` as `name`, with `patch` written at `at`.
  std::string copy(const std::string& from, const std::string& name, size_t bytes, size_t at = 0,
                   const std::string& patch = "") {
    std::ifstream in(from, std::ios::binary);
    std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    data = data.substr(0, bytes);
    data.replace(at, patch.size(), patch);
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << data;
    return path;
  }
  /// The message of reading `file` as body "Block".
  static std::string readError(const std::string& file) {
    ddc::Mesh m;
    Teuchos::ParameterList p;
    p.set("File", file);
    return inputErrorOf([&] { ddc::readExodusBody(m, "Block", ddc::CellType::Quad4, p, "Mesh/Bodies/Block/Exodus", "."); });
  }

  fs::path dir_;
};

TEST_F(ExodusMeshInput, AWholeFileEndsWhereItsHeaderSays) {
  const std::string file = write("whole.e");
  const ddc::NetcdfClassicExtent x = ddc::netcdfClassicExtent(file);
  EXPECT_TRUE(x.classic);
  EXPECT_TRUE(x.readable) << x.problem;
  EXPECT_EQ(x.end, double(fs::file_size(file))) << "the data of '" << x.variable << "'";
  EXPECT_EQ(readError(file), ddc::test::kNoInputError);
}

TEST_F(ExodusMeshInput, AFileCutShortInItsDataIsTruncated) {
  const std::string whole = write("whole.e");
  const std::string file = copy(whole, "cut.e", size_t(fs::file_size(whole)) - 8);
  const std::string msg = readError(file);
  EXPECT_NE(msg.find("Exodus II file '" + file + "': it has "), std::string::npos) << msg;
  EXPECT_NE(msg.find("the file is truncated (cut short) or its header is corrupt"), std::string::npos) << msg;
}

TEST_F(ExodusMeshInput, AFileCutInItsHeaderIsTruncated) {
  const std::string file = copy(write("whole.e"), "cut.e", 100);
  EXPECT_FALSE(ddc::netcdfClassicExtent(file).readable);
  const std::string msg = readError(file);
  EXPECT_NE(msg.find("its netCDF header cannot be read (the header ends early): the file is truncated"),
            std::string::npos)
      << msg;
}

TEST_F(ExodusMeshInput, AHeaderDeclaringMoreThanTheFileHoldsIsRefused) {
  const std::string whole = write("whole.e");
  std::ifstream in(whole, std::ios::binary);
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string name("num_nodes\0\0\0", 12);
  const size_t at = data.find(name);
  ASSERT_NE(at, std::string::npos);
  // 300 million as the 4 big-endian bytes of the dimension's length.
  const std::string n300M{char(0x11), char(0xE1), char(0xA3), char(0x00)};
  const std::string file = copy(whole, "huge.e", data.size(), at + name.size(), n300M);
  const std::string msg = readError(file);
  EXPECT_NE(msg.find("but its header places the data of variable 'coord"), std::string::npos) << msg;
  EXPECT_NE(msg.find("the file is truncated (cut short) or its header is corrupt"), std::string::npos) << msg;
}

TEST_F(ExodusMeshInput, CoordinatesBeyondTheLimitNameTheNode) {
  for (const double x : {1e300, std::numeric_limits<double>::quiet_NaN()}) {
    const std::string msg = readError(write("far.e", x));
    EXPECT_NE(msg.find("node 1 of element block"), std::string::npos) << msg;
    EXPECT_NE(msg.find(std::isnan(x) ? "has x = nan" : "has x = 1e+300"), std::string::npos) << msg;
    EXPECT_NE(msg.find("every coordinate must be a finite number within +-1e+100 (the coordinate limit"),
              std::string::npos)
        << msg;
  }
}

}  // namespace
