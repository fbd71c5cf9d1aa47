// Sample directions over the whole sphere, for the references of programs/ (program_references.h)
// and for the irradiance library's error measures (irradiance/sh/ground_truth.h).
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace vs11 {

// `count` unit normals spread evenly over the sphere by the Fibonacci (golden-angle) spiral: normal i
// has y = 1 - (2 i + 1) / count (+y is up) and azimuth i x the golden angle. Deterministic; empty for
// count <= 0.
std::vector<glm::dvec3> SphereNormals(int count);

}  // namespace vs11
