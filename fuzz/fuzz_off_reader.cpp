// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// libFuzzer target: the bytes are an OFF file, read from memory with CGAL::IO::read_OFF()
// into a Surface_mesh; when that succeeds and the mesh has at most 200 faces,
// spherical_parameterize() runs with number_of_iterations(20) and its invariants are
// checked (fuzz_common.h). Build and run: fuzz/run_fuzz.sh.
//
// CGAL 5.5.1's reader sizes a face's vector by the size it reads, as a double cast to
// std::size_t: a face of -3 or 3e18 vertices throws std::length_error out of read_OFF(),
// one of 3e8 vertices allocates 2.4 GB (findings/cgal_off_reader_*). Those are CGAL's,
// found and reported; so that the fuzzer gets past them to the package, std::length_error
// from the reader is caught and inputs with an integer of 7 digits or more are skipped.

#include "fuzz_common.h"

#include <CGAL/Surface_mesh/IO/OFF.h>

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>

namespace {

/// True if a run of 7 digits or more starts the integer part of a number (a run right
/// after a '.' is a fraction and is allowed).
bool has_huge_integer(const std::uint8_t* data, std::size_t size)
{
  std::size_t run = 0;
  bool fraction = false;
  for(std::size_t i = 0; i < size; ++i) {
    if(data[i] >= '0' && data[i] <= '9') {
      if(run++ == 0) fraction = i > 0 && data[i - 1] == '.';
      if(run >= 7 && !fraction) return true;
    } else {
      run = 0;
    }
  }
  return false;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if(has_huge_integer(data, size))
    return 0;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  fuzz::Mesh mesh;
  try {
    if(!CGAL::IO::read_OFF(in, mesh, CGAL::parameters::verbose(false)))
      return 0;
  } catch(const std::length_error&) {
    return 0;
  }
  fuzz::check_parameterization(mesh, CGAL::parameters::number_of_iterations(20));
  return 0;
}
