// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// FreeSurfer's binary triangle surfaces (`lh.white`, `lh.pial`, `lh.sphere`, ...), as the
// command line tool reads and writes them. The format, big-endian throughout:
//   3 bytes   0xFF 0xFF 0xFE (the triangle file's magic number)
//   a line    "created by ...", then an empty line
//   int32     vertex count, int32 face count
//   float32   x y z per vertex
//   int32     three vertex indices per face
//   bytes     optional tags to the end (the volume geometry, the command line), kept verbatim

#ifndef SPHERICAL_PARAMETERIZATION_EXAMPLES_FREESURFER_SURFACE_H
#define SPHERICAL_PARAMETERIZATION_EXAMPLES_FREESURFER_SURFACE_H

#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace freesurfer {

struct Surface
{
  std::vector<std::array<double, 3>> points;
  std::vector<std::vector<std::size_t>> triangles;
  std::string tags;  // what follows the faces, kept for a file written from this one
};

enum class File_kind { NOT_FREESURFER, TRIANGLES, QUADRANGLES };

// The kind of `path` by its magic number, whatever its name (FreeSurfer's have no extension):
// 0xFFFFFE triangles, 0xFFFFFF and 0xFFFFFD the old and new quadrangle formats.
inline File_kind file_kind(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  unsigned char magic[3] = {0, 0, 0};
  if(!in.read(reinterpret_cast<char*>(magic), 3) || magic[0] != 0xFF || magic[1] != 0xFF)
    return File_kind::NOT_FREESURFER;
  switch(magic[2]) {
  case 0xFE: return File_kind::TRIANGLES;
  case 0xFF:
  case 0xFD: return File_kind::QUADRANGLES;
  default: return File_kind::NOT_FREESURFER;
  }
}

namespace detail {

inline std::uint32_t big_endian_word(const unsigned char* b)
{
  return std::uint32_t(b[0]) << 24 | std::uint32_t(b[1]) << 16 | std::uint32_t(b[2]) << 8 | std::uint32_t(b[3]);
}

inline void put_big_endian_word(std::string& out, std::uint32_t w)
{
  for(int shift = 24; shift >= 0; shift -= 8)
    out.push_back(char((w >> shift) & 0xFF));
}

inline float word_as_float(std::uint32_t w)
{
  static_assert(sizeof(float) == sizeof(std::uint32_t), "float32 expected");
  float f;
  std::memcpy(&f, &w, sizeof f);
  return f;
}

inline std::uint32_t float_as_word(float f)
{
  std::uint32_t w;
  std::memcpy(&w, &f, sizeof w);
  return w;
}

} // namespace detail

// Reads a triangle surface; throws std::runtime_error naming what is wrong. The counts are
// checked against the file's size before anything is allocated, so a corrupted header
// fails cleanly instead of asking for gigabytes.
inline Surface read_surface(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if(!in.eof() && in.fail())
    throw std::runtime_error("cannot read the file");
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  if(bytes.size() < 3 || data[0] != 0xFF || data[1] != 0xFF || data[2] != 0xFE)
    throw std::runtime_error("not a FreeSurfer triangle surface");
  // The "created by" line and the empty line after it.
  std::size_t at = 3;
  for(int line = 0; line < 2; ++line) {
    const std::size_t end = bytes.find('\n', at);
    if(end == std::string::npos)
      throw std::runtime_error("truncated FreeSurfer surface (no end to its \"created by\" line)");
    at = end + 1;
  }
  if(bytes.size() - at < 8)
    throw std::runtime_error("truncated FreeSurfer surface (no vertex and face counts)");
  const std::uint32_t vertex_count = detail::big_endian_word(data + at);
  const std::uint32_t face_count = detail::big_endian_word(data + at + 4);
  at += 8;
  if(vertex_count > INT32_MAX || face_count > INT32_MAX || (bytes.size() - at) / 12 < std::uint64_t(vertex_count) + face_count)
    throw std::runtime_error("truncated FreeSurfer surface (" + std::to_string(vertex_count) + " vertices and " +
                             std::to_string(face_count) + " faces announced)");
  Surface s;
  s.points.resize(vertex_count);
  for(auto& p : s.points)
    for(double& c : p) {
      c = detail::word_as_float(detail::big_endian_word(data + at));
      at += 4;
    }
  s.triangles.assign(face_count, std::vector<std::size_t>(3));
  for(auto& t : s.triangles)
    for(std::size_t& v : t) {
      const std::int32_t index = std::int32_t(detail::big_endian_word(data + at));
      // A negative index becomes out of range, for the caller's check of the indices.
      v = index < 0 ? std::size_t(vertex_count) : std::size_t(index);
      at += 4;
    }
  s.tags = bytes.substr(at);
  return s;
}

// Writes a triangle surface, its points rounded to float32 as the format has them, with
// `tags` after the faces (those of the surface it was made from, or none).
inline bool write_surface(std::ostream& out, const std::vector<std::array<double, 3>>& points,
                          const std::vector<std::array<std::size_t, 3>>& triangles, const std::string& tags,
                          const std::string& creator)
{
  std::string bytes = "\xFF\xFF\xFE";
  bytes += "created by " + creator + "\n\n";
  detail::put_big_endian_word(bytes, std::uint32_t(points.size()));
  detail::put_big_endian_word(bytes, std::uint32_t(triangles.size()));
  for(const auto& p : points)
    for(double c : p)
      detail::put_big_endian_word(bytes, detail::float_as_word(float(c)));
  for(const auto& t : triangles)
    for(std::size_t v : t)
      detail::put_big_endian_word(bytes, std::uint32_t(v));
  bytes += tags;
  return bool(out.write(bytes.data(), std::streamsize(bytes.size())));
}

} // namespace freesurfer

#endif // SPHERICAL_PARAMETERIZATION_EXAMPLES_FREESURFER_SURFACE_H
