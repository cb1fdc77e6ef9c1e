// Hdf5File writes what it is given: every value is read back exactly with
// the plain HDF5 C API (not with Hdf5File itself, so a symmetric bug in
// writing and reading cannot hide).
#include "boomdyn/hdf5_file.hpp"
#include "boomdyn/output_file.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <mpi.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using boomdyn::Hdf5File;
using boomdyn::placementPath;
using boomdyn::specialFileKind;

namespace {

// Closes an HDF5 identifier at scope exit.
struct Id {
  hid_t id;
  herr_t (*closer)(hid_t);
  Id(hid_t i, herr_t (*c)(hid_t)) : id(i), closer(c) { EXPECT_GE(id, 0); }
  Id(const Id &) = delete;
  Id &operator=(const Id &) = delete;
  ~Id()
  {
    if (id >= 0)
      closer(id);
  }
  operator hid_t() const { return id; }
};

std::vector<hsize_t> shapeOf(hid_t dataset)
{
  Id space(H5Dget_space(dataset), H5Sclose);
  std::vector<hsize_t> dims(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return dims;
}

// A dataset read whole in the given memory type, with its shape.
template <typename T>
std::pair<std::vector<T>, std::vector<hsize_t>> readDataset(hid_t file, const std::string &path, hid_t memType)
{
  Id dataset(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose);
  std::vector<hsize_t> dims = shapeOf(dataset);
  std::size_t count = 1;
  for (hsize_t d : dims)
    count *= d;
  std::vector<T> values(count);
  if (count > 0) {
    EXPECT_GE(H5Dread(dataset, memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0) << path;
  }
  return {values, dims};
}

std::vector<double> readDoubles(hid_t file, const std::string &path, std::vector<hsize_t> expectedDims)
{
  auto [values, dims] = readDataset<double>(file, path, H5T_NATIVE_DOUBLE);
  EXPECT_EQ(dims, expectedDims) << path;
  return values;
}

std::vector<int> readInts(hid_t file, const std::string &path, std::vector<hsize_t> expectedDims)
{
  auto [values, dims] = readDataset<int>(file, path, H5T_NATIVE_INT);
  EXPECT_EQ(dims, expectedDims) << path;
  return values;
}

// Strings must be variable-length UTF-8 (what h5py turns into str most easily).
void expectVariableUtf8(hid_t type)
{
  EXPECT_EQ(H5Tget_class(type), H5T_STRING);
  EXPECT_GT(H5Tis_variable_str(type), 0);
  EXPECT_EQ(H5Tget_cset(type), H5T_CSET_UTF8);
}

std::vector<std::string> readStrings(hid_t file, const std::string &path)
{
  Id dataset(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose);
  Id type(H5Dget_type(dataset), H5Tclose);
  expectVariableUtf8(type);
  Id space(H5Dget_space(dataset), H5Sclose);
  std::vector<char *> pointers(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)), nullptr);
  if (!pointers.empty()) {
    EXPECT_GE(H5Dread(dataset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()), 0);
  }
  std::vector<std::string> texts;
  for (char *p : pointers) {
    texts.emplace_back(p ? p : "");
    H5free_memory(p);
  }
  return texts;
}

Id openAttribute(hid_t file, const std::string &object, const std::string &name)
{
  return Id(H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
}

std::string readStringAttribute(hid_t file, const std::string &object, const std::string &name)
{
  Id attribute = openAttribute(file, object, name);
  Id type(H5Aget_type(attribute), H5Tclose);
  expectVariableUtf8(type);
  char *text = nullptr;
  EXPECT_GE(H5Aread(attribute, type, &text), 0);
  std::string value = text ? text : "";
  H5free_memory(text);
  return value;
}

template <typename T>
T readScalarAttribute(hid_t file, const std::string &object, const std::string &name, hid_t memType)
{
  Id attribute = openAttribute(file, object, name);
  T value{};
  EXPECT_GE(H5Aread(attribute, memType, &value), 0);
  return value;
}

std::vector<double> readDoublesAttribute(hid_t file, const std::string &object, const std::string &name)
{
  Id attribute = openAttribute(file, object, name);
  Id space(H5Aget_space(attribute), H5Sclose);
  std::vector<double> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  if (!values.empty()) {
    EXPECT_GE(H5Aread(attribute, H5T_NATIVE_DOUBLE, values.data()), 0);
  }
  return values;
}

class Hdf5FileTest : public ::testing::Test {
protected:
  // One file per test and rank: the unit tests may run under mpiexec.
  std::string outputPath(const std::string &stem)
  {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    fs::path dir = fs::path(BOOMDYN_BINARY_DIR) / "test_output" / "hdf5_file";
    fs::create_directories(dir);
    fs::path file = dir / (stem + "_rank" + std::to_string(rank) + ".h5");
    fs::remove(file);
    return file.string();
  }

  static hid_t openReadOnly(const std::string &path) { return H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT); }
};

std::string messageOf(const std::function<void()> &action)
{
  try {
    action();
  } catch (const std::runtime_error &error) {
    return error.what();
  }
  ADD_FAILURE() << "no std::runtime_error thrown";
  return {};
}

} // namespace

TEST_F(Hdf5FileTest, AttributesRoundTripExactly)
{
  const std::string path = outputPath("attributes");
  const std::vector<double> gravity{0.0, -9.80665, 1.0 / 3.0, -2.5e-300};
  const double pi = std::acos(-1.0);
  {
    Hdf5File out(path, false);
    out.setAttribute("/", "scene_name", std::string("telescope 3 sections, Ausleger µ"));
    out.setAttribute("/", "analysis", "dynamic");     // a literal picks the string overload
    out.setAttribute("/", "mpi_ranks", 4);            // int goes through the integer template
    out.setAttribute("/", "big", 9007199254740993LL); // 2^53 + 1: not representable as double
    out.setAttribute("/", "pi", pi);
    out.setAttribute("/", "gravity", gravity);
    out.setAttribute("/", "empty_list", std::vector<double>{});
    out.setAttribute("/", "empty_text", std::string());
    out.setAttribute("/summary", "status", "interrupted"); // group made on demand
    out.setAttribute("summary", "status", "completed");    // replaced, same object
    out.setAttribute("/summary", "steps", std::size_t{12345});
    out.setAttribute("/a/b/c/", "depth", 3LL); // nested groups, trailing slash
    std::vector<double> data{1.0, 2.0};
    out.writeArray("/modal/frequencies_hz", data, {2});
    out.setAttribute("/modal/frequencies_hz", "state_time", 2.5); // on a dataset
    out.close();
  }
  hid_t raw = openReadOnly(path);
  ASSERT_GE(raw, 0);
  Id file(raw, H5Fclose);
  EXPECT_EQ(readStringAttribute(file, "/", "scene_name"), "telescope 3 sections, Ausleger µ");
  EXPECT_EQ(readStringAttribute(file, "/", "analysis"), "dynamic");
  EXPECT_EQ(readScalarAttribute<long long>(file, "/", "mpi_ranks", H5T_NATIVE_LLONG), 4);
  EXPECT_EQ(readScalarAttribute<long long>(file, "/", "big", H5T_NATIVE_LLONG), 9007199254740993LL);
  EXPECT_EQ(readScalarAttribute<double>(file, "/", "pi", H5T_NATIVE_DOUBLE), pi);
  EXPECT_EQ(readDoublesAttribute(file, "/", "gravity"), gravity);
  EXPECT_TRUE(readDoublesAttribute(file, "/", "empty_list").empty());
  EXPECT_EQ(readStringAttribute(file, "/", "empty_text"), "");
  EXPECT_EQ(readStringAttribute(file, "/summary", "status"), "completed");
  EXPECT_EQ(readScalarAttribute<long long>(file, "/summary", "steps", H5T_NATIVE_LLONG), 12345);
  EXPECT_EQ(readScalarAttribute<long long>(file, "/a/b/c", "depth", H5T_NATIVE_LLONG), 3);
  EXPECT_EQ(readScalarAttribute<double>(file, "/modal/frequencies_hz", "state_time", H5T_NATIVE_DOUBLE), 2.5);

  // Integers are stored as 64-bit integers, reals as 64-bit IEEE.
  Id steps = openAttribute(file, "/summary", "steps");
  Id stepsType(H5Aget_type(steps), H5Tclose);
  EXPECT_EQ(H5Tget_class(stepsType), H5T_INTEGER);
  EXPECT_EQ(H5Tget_size(stepsType), 8u);
  EXPECT_EQ(H5Aget_num_attrs(Id(H5Gopen2(file, "/summary", H5P_DEFAULT), H5Gclose)), 2);
}

TEST_F(Hdf5FileTest, StringsAndArraysRoundTripExactly)
{
  const std::string path = outputPath("arrays");
  const std::string scene = "name: luffing test\nbodies:\n  - {name: base, type: ancf_beam}\n# ünïcode\n";
  const std::vector<std::string> names{"base", "section_2", "", "tip µ"};
  const std::vector<double> matrix{1.0, -2.0, 1.0 / 3.0, 1e-310, 6.02214076e23, -0.0};
  const std::vector<int> firsts{0, 12, 24, -7};
  {
    Hdf5File out(path, false);
    out.writeString("/scene/text", scene);
    out.writeStrings("/layout/body_names", names);
    out.writeStrings("/layout/constraint_names", {});
    out.writeArray("/layout/matrix", matrix, {3, 2});
    out.writeArray("/layout/body_first_coordinate", firsts, {4});
    out.writeArray("/scalar", std::vector<double>{42.5}, {});
    out.writeArray("/empty", std::vector<double>{}, {0, 5});
  }
  Id file(openReadOnly(path), H5Fclose);
  EXPECT_EQ(readStrings(file, "/scene/text"), std::vector<std::string>{scene});
  EXPECT_EQ(shapeOf(Id(H5Dopen2(file, "/scene/text", H5P_DEFAULT), H5Dclose)), std::vector<hsize_t>{});
  EXPECT_EQ(readStrings(file, "/layout/body_names"), names);
  EXPECT_TRUE(readStrings(file, "/layout/constraint_names").empty());
  std::vector<double> matrixBack = readDoubles(file, "/layout/matrix", {3, 2});
  EXPECT_EQ(matrixBack, matrix);
  EXPECT_TRUE(std::signbit(matrixBack[5])); // bit-exact, not just ==
  EXPECT_EQ(readInts(file, "/layout/body_first_coordinate", {4}), firsts);
  EXPECT_EQ(readDoubles(file, "/scalar", {}), std::vector<double>{42.5});
  EXPECT_TRUE(readDoubles(file, "/empty", {0, 5}).empty());
}

TEST_F(Hdf5FileTest, AppendedRowsRoundTripExactly)
{
  const std::string path = outputPath("append");
  const std::size_t rows = 5000;
  const std::size_t wide = 40000; // one row is larger than a chunk's byte budget
  auto time = [](std::size_t i) { return 1e-3 * static_cast<double>(i) + 1.0 / 7.0; };
  {
    Hdf5File out(path, false);
    for (std::size_t i = 0; i < rows; ++i) {
      out.appendScalar("/steps/time", time(i));
      out.appendScalarInt("/steps/newton_iterations", static_cast<int>(i % 7));
      const double energy[4] = {time(i), -time(i), 2.0 * time(i), std::sqrt(time(i))};
      out.appendRow("/steps/energy", energy, 4);
      const int pair[2] = {static_cast<int>(i), -static_cast<int>(i)};
      out.appendRow("/counts", pair, 2);
      const double column = time(i);
      out.appendRow("/column", &column, 1); // stays 2-D: (n, 1)
    }
    std::vector<double> state(wide);
    for (std::size_t r = 0; r < 3; ++r) {
      for (std::size_t j = 0; j < wide; ++j)
        state[j] = static_cast<double>(r * wide + j);
      out.appendRow("/state/q", state.data(), wide);
    }
    out.appendScalar("steps//dt/", 0.25); // another spelling of one path is the same series
    out.appendScalar("/steps/dt", 0.5);
  }
  Id file(openReadOnly(path), H5Fclose);
  std::vector<double> t = readDoubles(file, "/steps/time", {rows});
  std::vector<int> iterations = readInts(file, "/steps/newton_iterations", {rows});
  std::vector<double> energy = readDoubles(file, "/steps/energy", {rows, 4});
  std::vector<int> counts = readInts(file, "/counts", {rows, 2});
  std::vector<double> column = readDoubles(file, "/column", {rows, 1});
  for (std::size_t i = 0; i < rows; ++i) {
    ASSERT_EQ(t[i], time(i)) << i;
    ASSERT_EQ(iterations[i], static_cast<int>(i % 7)) << i;
    ASSERT_EQ(energy[4 * i + 0], time(i)) << i;
    ASSERT_EQ(energy[4 * i + 1], -time(i)) << i;
    ASSERT_EQ(energy[4 * i + 2], 2.0 * time(i)) << i;
    ASSERT_EQ(energy[4 * i + 3], std::sqrt(time(i))) << i;
    ASSERT_EQ(counts[2 * i], static_cast<int>(i)) << i;
    ASSERT_EQ(counts[2 * i + 1], -static_cast<int>(i)) << i;
    ASSERT_EQ(column[i], time(i)) << i;
  }
  std::vector<double> q = readDoubles(file, "/state/q", {3, wide});
  for (std::size_t k = 0; k < q.size(); ++k)
    ASSERT_EQ(q[k], static_cast<double>(k)) << k;
  EXPECT_EQ(readDoubles(file, "/steps/dt", {2}), (std::vector<double>{0.25, 0.5}));

  // Extendible along the rows only, chunked.
  Id dataset(H5Dopen2(file, "/steps/energy", H5P_DEFAULT), H5Dclose);
  Id space(H5Dget_space(dataset), H5Sclose);
  hsize_t maxDims[2] = {0, 0};
  H5Sget_simple_extent_dims(space, nullptr, maxDims);
  EXPECT_EQ(maxDims[0], H5S_UNLIMITED);
  EXPECT_EQ(maxDims[1], 4u);
  Id layout(H5Dget_create_plist(dataset), H5Pclose);
  EXPECT_EQ(H5Pget_layout(layout), H5D_CHUNKED);
}

// writeGroup (the /paraview snapshots): the same datasets and attribute as
// writeArray and setAttribute would give, in a new group; an existing group
// or a wrong shape is refused with the path, and nothing is half-written.
TEST_F(Hdf5FileTest, GroupOfArraysRoundTripsExactly)
{
  const std::string path = outputPath("group");
  const std::vector<double> points{1.0, -2.0, 0.0, 1.0 / 3.0, 1e-310, -0.0}, strain{0.5, -0.25};
  {
    Hdf5File out(path, false);
    out.writeGroup("/paraview/0", {{"points", &points, {2, 3}}, {"axial_strain", &strain, {2}}}, "time", 0.125);
    out.writeGroup("paraview/1", {{"points", &points, {2, 3}}}, "time", 1.0 / 3.0);
    EXPECT_NE(messageOf([&] { out.writeGroup("/paraview/1", {{"points", &points, {2, 3}}}, "time", 0.0); })
                .find("/paraview/1"),
              std::string::npos);
    EXPECT_NE(messageOf([&] { out.writeGroup("/paraview/2", {{"points", &points, {3, 3}}}, "time", 0.0); })
                .find("/paraview/2/points"),
              std::string::npos);
  }
  Id file(openReadOnly(path), H5Fclose);
  const std::vector<double> back = readDoubles(file, "/paraview/0/points", {2, 3});
  EXPECT_EQ(back, points);
  EXPECT_TRUE(std::signbit(back[5]));
  EXPECT_EQ(readDoubles(file, "/paraview/0/axial_strain", {2}), strain);
  EXPECT_EQ(readDoubles(file, "/paraview/1/points", {2, 3}), points);
  EXPECT_EQ(readScalarAttribute<double>(file, "/paraview/0", "time", H5T_NATIVE_DOUBLE), 0.125);
  EXPECT_EQ(readScalarAttribute<double>(file, "/paraview/1", "time", H5T_NATIVE_DOUBLE), 1.0 / 3.0);
  EXPECT_EQ(H5Lexists(file, "/paraview/2", H5P_DEFAULT), 0);
}

TEST_F(Hdf5FileTest, MisuseIsRefusedWithThePath)
{
  const std::string path = outputPath("misuse");
  Hdf5File out(path, false);
  const double row[3] = {1, 2, 3};
  const int ints[3] = {1, 2, 3};
  out.appendRow("/steps/energy", row, 3);
  EXPECT_NE(messageOf([&] { out.appendRow("/steps/energy", row, 2); }).find("/steps/energy"), std::string::npos);
  EXPECT_NE(messageOf([&] { out.appendRow("/steps/energy", ints, 3); }).find(path), std::string::npos);
  EXPECT_NE(messageOf([&] { out.appendScalar("/steps/energy", 1.0); }).find("/steps/energy"), std::string::npos);
  EXPECT_NE(messageOf([&] { out.appendRow("/steps/none", row, 0); }).find("/steps/none"), std::string::npos);

  out.writeArray("/fixed", std::vector<double>{1, 2}, {2});
  EXPECT_NE(messageOf([&] { out.appendScalar("/fixed", 3.0); }).find("already exists"), std::string::npos);
  EXPECT_NE(messageOf([&] {
              out.writeArray("/fixed", std::vector<double>{1, 2}, {2});
            }).find("already exists"),
            std::string::npos);
  EXPECT_NE(messageOf([&] {
              out.writeArray("/shape", std::vector<double>{1, 2, 3}, {2, 2});
            }).find("/shape"),
            std::string::npos);
  // A dataset cannot hold groups: the HDF5 error becomes an exception naming file and object.
  std::string nested = messageOf([&] { out.writeString("/fixed/child", "x"); });
  EXPECT_NE(nested.find(path), std::string::npos) << nested;
  EXPECT_NE(nested.find("/fixed/child"), std::string::npos) << nested;

  // The file is still usable after refused calls.
  out.appendRow("/steps/energy", row, 3);
  out.close();
  Id file(openReadOnly(path), H5Fclose);
  EXPECT_EQ(readDoubles(file, "/steps/energy", {2, 3}), (std::vector<double>{1, 2, 3, 1, 2, 3}));
}

TEST_F(Hdf5FileTest, ExistingFileIsKeptUnlessOverwriteIsAsked)
{
  const std::string path = outputPath("overwrite");
  {
    Hdf5File first(path, false);
    first.setAttribute("/", "run", 1LL);
  }
  std::string message = messageOf([&] { Hdf5File again(path, false); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("overwrite"), std::string::npos) << message;
  {
    Id file(openReadOnly(path), H5Fclose); // refused: the old run is intact
    EXPECT_EQ(readScalarAttribute<long long>(file, "/", "run", H5T_NATIVE_LLONG), 1);
  }
  {
    Hdf5File second(path, true);
    second.setAttribute("/", "run", 2LL);
  }
  Id file(openReadOnly(path), H5Fclose);
  EXPECT_EQ(readScalarAttribute<long long>(file, "/", "run", H5T_NATIVE_LLONG), 2);
}

// A FIFO or a folder at the path is never replaced, with or without
// overwrite (a rename onto /dev/null replaced the device); a symbolic link
// to a regular file is written through and stays a link.
TEST_F(Hdf5FileTest, SpecialFilesAreRefusedAndLinksWrittenThrough)
{
  const std::string fifo = outputPath("fifo"), folder = outputPath("folder");
  fs::remove_all(folder);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  fs::create_directory(folder);
  EXPECT_EQ(specialFileKind(fifo), "a FIFO (named pipe)");
  EXPECT_EQ(specialFileKind(folder), "a folder");
  EXPECT_EQ(specialFileKind(fifo + ".absent"), "");
  for (const std::string &path : {fifo, folder}) {
    const std::string message = messageOf([&] { Hdf5File out(path, true); });
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("not a regular file"), std::string::npos) << message;
  }
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_TRUE(fs::is_directory(folder));
  fs::remove(fifo);
  fs::remove(folder);

  const std::string target = outputPath("link_target"), link = outputPath("link");
  { Hdf5File first(target, false); }
  fs::create_symlink(target, link);
  EXPECT_EQ(placementPath(link), fs::canonical(target).string());
  EXPECT_EQ(placementPath(target), target);
  {
    Hdf5File through(link, true);
    through.setAttribute("/", "run", 3LL);
  }
  EXPECT_TRUE(fs::is_symlink(link));
  Id file(openReadOnly(target), H5Fclose);
  EXPECT_EQ(readScalarAttribute<long long>(file, "/", "run", H5T_NATIVE_LLONG), 3);
}

TEST_F(Hdf5FileTest, UnwritableLocationNamesThePath)
{
  const std::string path = outputPath("x") + ".missing_dir/run.h5";
  std::string message = messageOf([&] { Hdf5File out(path, false); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
}

// What is on disk right after flush() is a complete file: a copy taken while
// the writer still has it open (what a crash would leave) reads back fully.
TEST_F(Hdf5FileTest, FlushedFileOnDiskIsReadableWhileOpen)
{
  const std::string path = outputPath("flush");
  const std::string snapshot = outputPath("flush_snapshot");
  Hdf5File out(path, false);
  out.setAttribute("/", "scene_name", "flush test");
  out.writeStrings("/layout/body_names", {"base"});
  for (int i = 0; i < 1000; ++i) {
    out.appendScalar("/steps/time", 0.001 * i);
    const double xy[2] = {1.0 * i, -1.0 * i};
    out.appendRow("/sensors/tip/position", xy, 2);
  }
  out.flush();
  fs::copy_file(path, snapshot, fs::copy_options::overwrite_existing);
  out.appendScalar("/steps/time", 1.0); // keeps writing after the snapshot
  {
    Id file(openReadOnly(snapshot), H5Fclose);
    EXPECT_EQ(readStringAttribute(file, "/", "scene_name"), "flush test");
    EXPECT_EQ(readStrings(file, "/layout/body_names"), std::vector<std::string>{"base"});
    std::vector<double> t = readDoubles(file, "/steps/time", {1000});
    std::vector<double> xy = readDoubles(file, "/sensors/tip/position", {1000, 2});
    for (int i = 0; i < 1000; ++i) {
      ASSERT_EQ(t[i], 0.001 * i);
      ASSERT_EQ(xy[2 * i + 1], -1.0 * i);
    }
  }
  out.close();
  Id file(openReadOnly(path), H5Fclose);
  EXPECT_EQ(readDoubles(file, "/steps/time", {1001})[1000], 1.0);
}

TEST_F(Hdf5FileTest, CloseIsIdempotentAndEndsWriting)
{
  const std::string path = outputPath("close");
  Hdf5File out(path, false);
  EXPECT_TRUE(out.isOpen());
  EXPECT_EQ(out.path(), path);
  out.appendScalar("/steps/time", 1.0);
  EXPECT_TRUE(out.exists("/steps/time"));
  EXPECT_TRUE(out.exists("steps"));
  EXPECT_TRUE(out.exists("/"));
  EXPECT_FALSE(out.exists("/steps/dt"));
  EXPECT_FALSE(out.exists("/nothing/here"));
  out.close();
  out.close();
  EXPECT_FALSE(out.isOpen());
  EXPECT_NE(messageOf([&] { out.appendScalar("/steps/time", 2.0); }).find("closed"), std::string::npos);
  EXPECT_THROW(out.flush(), std::runtime_error);

  // The file is fully released: it can be replaced right away.
  Hdf5File again(path, true);
  EXPECT_TRUE(again.isOpen());
}

TEST_F(Hdf5FileTest, MovedFileKeepsWritingTheSameSeries)
{
  const std::string path = outputPath("move");
  Hdf5File first(path, false);
  first.appendScalar("/steps/time", 1.0);
  Hdf5File second(std::move(first));
  EXPECT_FALSE(first.isOpen()); // NOLINT(bugprone-use-after-move): moved-from state is specified
  EXPECT_THROW(first.appendScalar("/steps/time", 9.0), std::runtime_error);
  second.appendScalar("/steps/time", 2.0);
  second.close();
  Id file(openReadOnly(path), H5Fclose);
  EXPECT_EQ(readDoubles(file, "/steps/time", {2}), (std::vector<double>{1.0, 2.0}));
}
