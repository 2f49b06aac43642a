// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PIPELINE_FLOOR_PATCH_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PIPELINE_FLOOR_PATCH_H

#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>

#include <array>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// The neighbourhood of some faces of a soup, as a soup of its own: the vertices within
/// `rings` rings of those faces come first and are the unknowns (`free_vertices`); the
/// faces around them bring the vertices of the ring beyond, held where they are.
struct Floor_patch
{
  Triangle_soup soup;          ///< points and reference shapes of the input, faces re-indexed
  std::vector<int> to_input;   ///< the input vertex of each patch vertex
  std::size_t free_vertices = 0;
};

/// The faces around each vertex, as offsets into one array.
struct Vertex_faces
{
  std::vector<int> offset, faces;

  explicit Vertex_faces(const Triangle_soup& soup)
    : offset(soup.number_of_vertices() + 1, 0), faces(3 * soup.number_of_faces())
  {
    for(const auto& t : soup.faces)
      for(int v : t)
        ++offset[v + 1];
    for(std::size_t v = 0; v < soup.number_of_vertices(); ++v)
      offset[v + 1] += offset[v];
    std::vector<int> next(offset.begin(), offset.end() - 1);
    for(std::size_t f = 0; f < soup.number_of_faces(); ++f)
      for(int v : soup.faces[f])
        faces[next[v]++] = int(f);
  }
};

/// The patch of the vertices within `rings` rings of the faces `seed_faces` of `soup` (ring 0:
/// their own vertices).
inline Floor_patch make_floor_patch(const Triangle_soup& soup, const std::vector<int>& seed_faces, int rings)
{
  const Vertex_faces around(soup);
  constexpr int none = -1;
  std::vector<int> patch_index(soup.number_of_vertices(), none);
  Floor_patch patch;
  std::vector<int>& vertices = patch.to_input;
  auto add = [&](int v) {
    if(patch_index[v] == none) {
      patch_index[v] = int(vertices.size());
      vertices.push_back(v);
    }
  };
  for(int f : seed_faces)
    for(int v : soup.faces[f])
      add(v);
  // Ring by ring: the vertices of the faces around the last ring's vertices.
  std::size_t ring_begin = 0;
  for(int ring = 0; ring < rings; ++ring) {
    const std::size_t ring_end = vertices.size();
    for(std::size_t i = ring_begin; i < ring_end; ++i) {
      const int v = vertices[i];
      for(int k = around.offset[v]; k < around.offset[v + 1]; ++k)
        for(int w : soup.faces[around.faces[k]])
          add(w);
    }
    ring_begin = ring_end;
  }
  patch.free_vertices = vertices.size();

  // Every face around a free vertex; their other vertices are held.
  std::vector<char> taken(soup.number_of_faces(), 0);
  for(std::size_t i = 0; i < patch.free_vertices; ++i) {
    const int v = vertices[i];
    for(int k = around.offset[v]; k < around.offset[v + 1]; ++k) {
      const int f = around.faces[k];
      if(taken[f])
        continue;
      taken[f] = 1;
      std::array<int, 3> t = soup.faces[f];
      for(int& w : t) {
        add(w);
        w = patch_index[w];
      }
      patch.soup.faces.push_back(t);
    }
  }
  for(int v : vertices) {
    patch.soup.points.push_back(soup.points[v]);
    if(!soup.vertex_scales.empty())
      patch.soup.vertex_scales.push_back(soup.vertex_scales[v]);
  }
  return patch;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PIPELINE_FLOOR_PATCH_H
