#pragma once
// What light does at a smooth interface between two clear media.
#include <optional>

#include <glm/glm.hpp>

namespace airr {

// Unpolarised Fresnel reflectance of a dielectric interface; cos_i is the cosine of the incidence
// angle and eta = n_transmitted / n_incident. Total internal reflection gives 1.
double fresnel_dielectric(double cos_i, double eta);

// Refracts the propagation direction d at a surface with normal m facing against d;
// ratio = n_incident / n_transmitted. Empty on total internal reflection.
std::optional<glm::dvec3> refract(const glm::dvec3& d, const glm::dvec3& m, double ratio);

}  // namespace airr
