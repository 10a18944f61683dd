// Writes the seed corpus of every harness: a few small valid files per format, made with the
// libraries' own writers (OpenVDB, VTK, isocurv's mesh writers) or spelled out by hand.
// Usage: isocurv_fuzz_seeds OUTDIR   (writes OUTDIR/<harness>/<name>)
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStructuredPointsWriter.h>
#include <vtkUnsignedShortArray.h>
#include <vtkXMLImageDataWriter.h>
#include <zlib.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/mesh_file.h"

namespace fs = std::filesystem;
using Bytes = std::string;

namespace {

fs::path out_dir;

void put(const std::string& harness, const std::string& name, const Bytes& bytes) {
  fs::create_directories(out_dir / harness);
  std::ofstream(out_dir / harness / name, std::ios::binary) << bytes;
}

Bytes slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

Bytes deflate(const Bytes& in, bool gzip) {
  z_stream zs{};
  deflateInit2(&zs, 9, Z_DEFLATED, gzip ? 15 + 16 : 15, 8, Z_DEFAULT_STRATEGY);
  Bytes out(deflateBound(&zs, uLong(in.size())) + 64, '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
  zs.avail_in = uInt(in.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = uInt(out.size());
  deflate(&zs, Z_FINISH);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

/// A 4x3x2 ramp, X fastest, as `T` in little-endian (the host's order here).
template <class T>
Bytes ramp(bool big_endian = false) {
  Bytes out;
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 4; ++x) {
        const T v = T(x + 4 * y + 12 * z);
        char b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        if (big_endian)
          for (std::size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(b[k], b[sizeof(T) - 1 - k]);
        out.append(b, sizeof(T));
      }
  return out;
}

const std::string kSplit = "\n#isocurv-fuzz-data#\n";  // fuzz_volume.cpp's header/data split

void vdb_seeds() {
  openvdb::initialize();
  const fs::path tmp = out_dir / "tmp.vdb";
  auto write = [&](const std::string& name, openvdb::GridBase::Ptr grid, std::uint32_t compression) {
    openvdb::io::File file(tmp.string());
    file.setCompression(compression);
    file.write(openvdb::GridPtrVec{grid});
    file.close();
    put("vdb", name, slurp(tmp));
    fs::remove(tmp);
  };
  auto ls = openvdb::FloatGrid::create(2.0f);
  ls->setName("ls");
  ls->setGridClass(openvdb::GRID_LEVEL_SET);
  for (int i = 0; i < 4; ++i) ls->tree().setValue(openvdb::Coord(i, i % 2, 0), float(i) - 1.5f);
  write("levelset_blosc.vdb", ls, openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK);
  write("levelset_zip.vdb", ls, openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK);
  auto fog = openvdb::DoubleGrid::create(0.0);
  fog->setName("fog");
  fog->setGridClass(openvdb::GRID_FOG_VOLUME);
  fog->tree().setValue(openvdb::Coord(3, 2, 1), 1.0);
  fog->tree().setValue(openvdb::Coord(-1, 0, 2), 0.5);
  write("fog_double.vdb", fog, openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK);
  auto half = ls->deepCopy();
  half->setSaveFloatAsHalf(true);
  write("levelset_half.vdb", half, openvdb::io::COMPRESS_ACTIVE_MASK);
}

void nrrd_seeds() {
  const std::string head = "NRRD0004\ndimension: 3\nsizes: 4 3 2\n";
  put("nrrd", "uchar_raw.nrrd", head + "type: uchar\nencoding: raw\nspacings: 1 1 2\n\n" + ramp<std::uint8_t>());
  put("nrrd", "short_gzip.nrrd",
      head + "type: short\nendian: big\nencoding: gzip\nspace origin: (1,2,3)\n"
             "space directions: (1,0,0) (0,0.5,0) (0,0,2)\n\n" + deflate(ramp<std::int16_t>(true), true));
  put("nrrd", "float_ascii.nrrd",
      head + "type: float\nencoding: ascii\n\n0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23\n");
  put("nrrd", "skip.nrrd", head + "type: uint16\nendian: little\nencoding: raw\nbyte skip: -1\nline skip: 1\n\n"
                                   "junk line\n" + ramp<std::uint16_t>());
  put("nhdr", "detached.nhdr",
      head + "type: int\nendian: little\nencoding: raw\ndata file: data.raw\n" + kSplit + ramp<std::int32_t>());
  put("nhdr", "detached_gz.nhdr",
      head + "type: double\nendian: little\nencoding: gzip\ndata file: data.raw\n" + kSplit +
          deflate(ramp<double>(), true));
}

void metaimage_seeds() {
  const std::string head = "ObjectType = Image\nNDims = 3\nDimSize = 4 3 2\n";
  put("mha", "uchar.mha", head + "ElementType = MET_UCHAR\nElementSpacing = 1 1 1.5\nElementDataFile = LOCAL\n" +
                               ramp<std::uint8_t>());
  put("mha", "short_zlib.mha",
      head + "ElementType = MET_SHORT\nBinaryDataByteOrderMSB = True\nCompressedData = True\n"
             "TransformMatrix = 0 1 0 1 0 0 0 0 1\nOffset = 1 2 3\nElementDataFile = LOCAL\n" +
          deflate(ramp<std::int16_t>(true), false));
  put("mha", "float_ascii.mha", head + "ElementType = MET_FLOAT\nBinaryData = False\nElementDataFile = LOCAL\n"
                                     "0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23\n");
  put("mhd", "ushort.mhd", head + "ElementType = MET_USHORT\nHeaderSize = -1\nElementDataFile = data.raw" + kSplit +
                               "pad" + ramp<std::uint16_t>());
  put("mhd", "double.mhd", head + "ElementType = MET_DOUBLE\nElementDataFile = data.raw" + kSplit + ramp<double>());
}

Bytes nifti(std::int16_t datatype, const Bytes& voxels, bool sform) {
  Bytes h(352, '\0');
  auto set = [&](std::size_t offset, auto value) { std::memcpy(&h[offset], &value, sizeof value); };
  set(0, std::int32_t(348));
  const std::int16_t dims[5] = {3, 4, 3, 2, 1};
  std::memcpy(&h[40], dims, sizeof dims);
  set(70, datatype);
  const float pixdim[4] = {1, 1, 1, 2};
  std::memcpy(&h[76], pixdim, sizeof pixdim);
  set(108, 352.0f);
  set(112, 2.0f);  // scl_slope
  set(116, 1.0f);  // scl_inter
  if (sform) {
    set(254, std::int16_t(1));
    const float srow[12] = {-1, 0, 0, 3, 0, 1, 0, 0, 0, 0, 2, -1};
    std::memcpy(&h[280], srow, sizeof srow);
  } else {
    set(252, std::int16_t(1));
    set(256, 0.0f), set(260, 0.0f), set(264, 1.0f);  // quaternion b c d: 180 degrees about z
  }
  std::memcpy(&h[344], "n+1", 4);
  return h + voxels;
}

void nifti_seeds() {
  put("nii", "int16_sform.nii", nifti(4, ramp<std::int16_t>(), true));
  put("nii", "uint8_qform.nii", nifti(2, ramp<std::uint8_t>(), false));
  put("nii", "float.nii", nifti(16, ramp<float>(), true));
  put("nii_gz", "int16_sform.nii.gz", deflate(nifti(4, ramp<std::int16_t>(), true), true));
  put("nii_gz", "uint16.nii.gz", deflate(nifti(512, ramp<std::uint16_t>(), false), true));
}

void vtk_image_seeds() {
  vtkNew<vtkImageData> image;
  image->SetDimensions(4, 3, 2);
  image->SetSpacing(1, 0.5, 2);
  image->SetOrigin(1, 2, 3);
  vtkNew<vtkUnsignedShortArray> values;
  values->SetName("density");
  values->SetNumberOfTuples(24);
  for (int i = 0; i < 24; ++i) values->SetValue(i, static_cast<unsigned short>(i * 10));
  image->GetPointData()->SetScalars(values);
  const fs::path tmp = out_dir / "tmp.vt";
  auto xml = [&](const std::string& name, int mode, bool compress) {
    vtkNew<vtkXMLImageDataWriter> w;
    w->SetInputData(image);
    w->SetFileName(tmp.string().c_str());
    w->SetDataMode(mode);
    if (!compress) w->SetCompressorTypeToNone();
    w->Write();
    put("vti", name, slurp(tmp));
  };
  xml("ascii.vti", vtkXMLWriter::Ascii, false);
  xml("binary.vti", vtkXMLWriter::Binary, false);
  xml("appended_zlib.vti", vtkXMLWriter::Appended, true);
  auto legacy = [&](const std::string& name, bool binary) {
    vtkNew<vtkStructuredPointsWriter> w;
    w->SetInputData(image);
    w->SetFileName(tmp.string().c_str());
    if (binary) w->SetFileTypeToBinary();
    w->Write();
    put("vtk", name, slurp(tmp));
  };
  legacy("ascii.vtk", false);
  legacy("binary.vtk", true);
  fs::remove(tmp);
  // SLC: header, a 1x1 icon (three colour planes), then the planes, raw or run-length coded.
  const std::string slc_head = "11111\n4 3 2 8\n1.0 1.0 2.0\n0 0 0 ";
  put("slc", "raw.slc", slc_head + "0\n1 1 X" + "abc" + ramp<std::uint8_t>());
  Bytes rle;
  for (int z = 0; z < 2; ++z) {
    // a copy code (high bit) of 12 bytes, then the terminator
    const Bytes plane = "\x8c" + ramp<std::uint8_t>().substr(std::size_t(12 * z), 12) + Bytes(1, '\0');
    rle += std::to_string(plane.size()) + " X" + plane;
  }
  put("slc", "rle.slc", slc_head + "1\n1 1 X" + "abc" + rle);
}

void vol_seeds() {
  const std::string head = "Center-X: 2\nCenter-Y: 1\nCenter-Z: 1\nX: 4\nY: 3\nZ: 2\nVoxel-Size: 1.5\n"
                           "Alpha-Color: 0\nVoxel-Endian: 0\nInt-Endian: 0123\n";
  put("vol", "v2.vol", head + "Version: 2\n.\n" + ramp<std::uint8_t>());
  put("vol", "v3.vol", head + "Version: 3\n.\n" + deflate(ramp<std::uint8_t>(), false));
}

void raw_seeds() {
  // The harness's first 6 bytes: dims - 1, type (0 uint8 .. 7 double), big endian, layout in name.
  put("raw", "uint8_options.raw", Bytes("\x03\x02\x01\x00\x00\x00", 6) + ramp<std::uint8_t>());
  put("raw", "int16be_name.raw", Bytes("\x03\x02\x01\x03\x01\x01", 6) + ramp<std::int16_t>(true));
  put("raw", "float_options.raw", Bytes("\x03\x02\x01\x06\x00\x00", 6) + ramp<float>());
  put("raw_gz", "uint16_name.raw.gz", Bytes("\x03\x02\x01\x02\x00\x01", 6) + deflate(ramp<std::uint16_t>(), true));
  put("raw_gz", "double_options.raw.gz", Bytes("\x03\x02\x01\x07\x00\x00", 6) + deflate(ramp<double>(), true));
}

void mesh_seeds() {
  // An octahedron with normals and a few curvature arrays.
  isocurv::Mesh mesh;
  mesh.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  mesh.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  isocurv::curvature::CurvatureField field;
  field.normals.assign(mesh.positions.begin(), mesh.positions.end());
  field.k1 = field.k2 = field.H = field.K = std::vector<float>(6, 1.0f);
  field.dir1 = std::vector<isocurv::Vec3f>(6, isocurv::Vec3f{0, 0, 1});
  field.boundary = std::vector<std::uint8_t>(6, 0);
  for (const char* ext : {"vtp", "ply", "obj", "stl"}) {
    const fs::path p = out_dir / (std::string("octahedron.") + ext);
    isocurv::io::write_mesh(p.string(), mesh, &field);
    put(ext, std::string("octahedron.") + ext, slurp(p));
    fs::remove(p);
  }
  put("ply", "ascii_quad.ply",
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "property float k1\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\n4 0 1 2 3\n");
  put("ply", "big_endian.ply",
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
      "property double z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n" +
          Bytes(3 * 3 * 8, '\0') + Bytes("\x03\0\0\0\0\0\0\0\x01\0\0\0\x02", 13));
  put("obj", "quad_negative.obj", "# quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\n"
                                  "f -4/1/1 -3/1/1 -2/1/1 -1/1/1\ng x\nf 1//1 2//1 3//1\n");
  put("stl", "ascii.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                          "endloop\nendfacet\nendsolid t\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: isocurv_fuzz_seeds OUTDIR\n");
    return 2;
  }
  out_dir = argv[1];
  fs::create_directories(out_dir);
  vdb_seeds();
  nrrd_seeds();
  metaimage_seeds();
  nifti_seeds();
  vtk_image_seeds();
  vol_seeds();
  raw_seeds();
  mesh_seeds();
  return 0;
}
