#pragma once
// The microfacet retroreflector (spec 2.3): a prism sheet of index eta with aluminium-coated
// cube-corner prisms. Light reflects off the front surface (Fresnel), or refracts in and is either
// retroreflected by three rough mirror faces and refracts out, or leaves in a Lambertian lobe.
#include <vector>

#include <glm/glm.hpp>

#include "airr/models/dielectric.hpp"
#include "airr/models/model_params.hpp"
#include "airr/models/polarization.hpp"
#include "airr/models/retro_model.hpp"

namespace airr {

// Beckmann normal distribution about +z, normalised so that the integral of D(m) cos(theta_m)
// over the hemisphere is 1. alpha > 0.
double beckmann_d(const glm::dvec3& m, double alpha);

// Microfacet normal about +z with density beckmann_d(m, alpha) * cos(theta_m); u1, u2 in [0, 1).
glm::dvec3 sample_beckmann(double alpha, double u1, double u2);

// Smith masking of direction w (w.z > 0) on a Beckmann surface of roughness alpha.
double smith_g1_beckmann(const glm::dvec3& w, double alpha);

// Density (per solid angle) of the normals visible from wi (wi.z > 0):
// smith_g1_beckmann(wi) * max(0, wi.m) * beckmann_d(m) / wi.z, which integrates to 1.
double beckmann_visible_d(const glm::dvec3& wi, const glm::dvec3& m, double alpha);

// Microfacet normal drawn from beckmann_visible_d(wi, ., alpha): the facet a ray arriving
// against wi meets, in proportion to its projected area. alpha = 0 gives +z.
glm::dvec3 sample_beckmann_visible(const glm::dvec3& wi, double alpha, double u1, double u2);

// Effective retroreflective area ERA(x, phi) of the prism sheet: x is the internal incidence
// angle and phi the azimuth, both in degrees.
double era(double x_deg, double phi_deg);

// Which path a sample took; a path that was absorbed on the way still reports it (weight 0).
enum class microfacet_branch { none, surface, retro, diffuse };

struct microfacet_trace {
  retro_sample sample;
  microfacet_branch branch = microfacet_branch::none;
};

// Random numbers per interaction (retro_samples):
//   lobe      x: Fresnel reflect / refract in, y: retroreflect / Lambertian
//   shift     retro: x the prism orientation, y the first face; diffuse: the cosine-weighted direction
//   more      in order: the front-surface facet on entry (2); retro: the first facet (2), the second
//             face (1), the second and third facets (2 + 2), the front-surface facet on exit (2).
struct microfacet_params {
  double alpha_surface = 0.0;
  double alpha_internal = 0.0005;
  double internal_reflectance = 0.83;
  double eta = 1.5046;
  double mu = 1.0;
  // A fitted Mueller matrix of the retroreflected light per incidence angle (a preset's, as the
  // sinc-shift model takes it); empty: the identity (the field kept as by a mirror facing the light).
  std::vector<double> polarization_theta_deg;
  std::vector<mueller> polarization;
};

// The model's scene-file entry ("microfacet").
const retro_model_kind& microfacet_retro_kind();

class microfacet_retro final : public retro_model {
 public:
  explicit microfacet_retro(const microfacet_params& p);
  retro_sample sample(const glm::dvec3& wi, retro_samples u) const override;
  // With the fitted Mueller matrix at wi's incidence on the retroreflected branch (the front
  // surface's reflection and the diffuse lobe: none).
  retro_sample sample_polarized(const glm::dvec3& wi, retro_samples u) const override;
  // The same sample, with the branch it took (for tests and analysis).
  microfacet_trace trace(const glm::dvec3& wi, retro_samples u) const;

 private:
  std::vector<double> polarization_theta_deg_;
  std::vector<mueller> polarization_;
  double alpha_surface_;
  double alpha_internal_;
  double internal_reflectance_;
  double eta_;
  double mu_;
};

}  // namespace airr
