// simplifyMesh() of a build without CGAL (libcgal-dev not found): E_s cannot be measured.
#include "cgal/simplify.h"

namespace lodline {

Result<SimplifyOutcome> simplifyMesh(const TriMesh&, double, const std::string& what) {
  return Error::runtime(what + ": lodline was built without CGAL (libcgal-dev): cannot measure E_s");
}

}  // namespace lodline
