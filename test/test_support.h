// The small harness shared by the test programs: PASS/FAIL/SKIP lines, counters, and the
// random helpers. Each program seeds `rng` at the start of main and prints its own
// closing "N passed, M failed" line.

#ifndef SPHERICAL_PARAMETERIZATION_TEST_SUPPORT_H
#define SPHERICAL_PARAMETERIZATION_TEST_SUPPORT_H

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <iostream>
#include <random>
#include <sstream>
#include <string>

namespace test_support {

inline int passed = 0, failed = 0, skipped = 0;

inline void report(const std::string& name, bool ok, const std::string& why = std::string())
{
  std::cout << (ok ? "PASS " : "FAIL ") << name;
  if(!ok && !why.empty())
    std::cout << "  (" << why << ")";
  std::cout << std::endl;
  ++(ok ? passed : failed);
}

inline void skip(const std::string& name, const std::string& why)
{
  std::cout << "SKIP " << name << "  (" << why << ")" << std::endl;
  ++skipped;
}

// The exit status by which a program tells CTest that it could not run all its checks because
// files it reads (CGAL's meshes, data/) are absent: test/CMakeLists.txt gives its tests
// SKIP_RETURN_CODE 77, so CTest lists them as skipped, never as passed.
inline constexpr int missing_data_exit_code = 77;

// A program's exit status: 1 when a check failed (whatever was missing), else 77 when
// `data_missing`, else 0.
inline int exit_status(bool data_missing)
{
  if(failed != 0)
    return 1;
  if(data_missing) {
    std::cout << "files missing: reported to CTest as skipped" << std::endl;
    return missing_data_exit_code;
  }
  return 0;
}

inline std::string str(double v, int precision = 4)
{
  std::ostringstream s;
  s.precision(precision);
  s << v;
  return s.str();
}

inline std::mt19937_64 rng;

inline double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

inline Eigen::Vector3d random_unit_vector()
{
  std::normal_distribution<double> normal;
  Eigen::Vector3d v;
  do v = Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
  while(v.norm() < 1e-3);
  return v.normalized();
}

inline Eigen::Matrix3d random_rotation()
{
  std::normal_distribution<double> normal;
  Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  q.normalize();
  return q.toRotationMatrix();
}

} // namespace test_support

#endif // SPHERICAL_PARAMETERIZATION_TEST_SUPPORT_H
