#pragma once
// A sheet whose microstructure is a designer's mesh: a clear plate whose back repeats one tile
// (a glTF mesh, say drawn in CAD) on a rectangular lattice. Light refracts in through the front
// surface and meets the tile's faces: total internal reflection with Fresnel loss, or a metal coat
// where the face's glTF material is metallic (metallic >= 0.5; its reflectance is the mean of the
// material's base colour). The tile is an Embree scene instanced over its cell and the eight cells
// around it, and a ray walks the lattice cell by cell, so memory holds one tile whatever the
// sheet's size. The shipped tile is a block of triangular cube corners (the prism sheet's).
//
// Sheet-local frame: the front surface is z = 0, light arriving from z > 0; the tile's highest
// point lies plate_mm below it. Tile frame: the file's x, y (rotated by azimuth_deg in the sheet),
// its cell [0, period_x) x [0, period_y). Its triangles may reach into the neighbouring cells (a
// whole cube corner across a cell's edge), by less than a period.
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "airr/core/embree.hpp"
#include "airr/core/mesh.hpp"
#include "airr/core/polygon.hpp"
#include "airr/core/random.hpp"
#include "airr/models/diffraction.hpp"
#include "airr/models/prism_sheet.hpp"
#include "airr/models/retro_model.hpp"

namespace airr {

struct tile_sheet_geometry {
  std::shared_ptr<const triangle_mesh> tile;  // mm
  std::string tile_file;                      // for errors
  glm::dvec2 period_mm{2 * 0.1 / 1.7320508075688772, 0.2};
  double index = 1.5;
  double plate_mm = 0.1;
  double azimuth_deg = 0;
  // Light out of the front spreads by the Fraunhofer pattern of the entry points that follow the
  // same faces (retroreflected light) or of the first face's (other light); 0: no diffraction.
  double wavelength_nm = 550;
  diffracted_light light = diffracted_light::single;
};

// The shipped tile: triangular cube corners at 0.1 mm pitch, azimuth 0 (period 2 pitch / sqrt 3
// along x, 2 pitch along y).
std::string default_tile_path();

// The tile built for tracing: its faces (coplanar triangles sharing edges) and the Embree scene of
// its nine instances. Throws input_error naming the tile's file for a tile that cannot be traced.
class tile_structure {
 public:
  explicit tile_structure(const tile_sheet_geometry& g);
  tile_structure(const tile_structure&) = delete;
  tile_structure& operator=(const tile_structure&) = delete;
  ~tile_structure();

  struct face {
    glm::dvec3 normal{0, 0, 1};       // unit, either side
    double offset = 0;                // normal . x on the face
    std::vector<glm::dvec3> outline;  // the convex hull of its triangles, tile frame (mm)
    std::optional<double> metal_reflectance;
  };
  const std::vector<face>& faces() const { return faces_; }
  double top_mm() const { return top_; }                // tile frame z of the highest point
  double bottom_mm() const { return bottom_; }          // and of the lowest
  RTCScene scene() const;                               // tile frame (mm)
  int face_of(unsigned triangle) const;                 // an Embree triangle's face
  glm::dvec2 instance_offset(unsigned instance) const;  // of an instance's cell, in periods
  std::size_t memory_bytes() const;                     // Embree's, for the tile and its instances

 private:
  std::vector<face> faces_;
  std::vector<int> triangle_face_;
  double top_ = 0, bottom_ = 0;
  embree_device device_;  // its own, so that its memory is the tile's
  std::unique_ptr<embree_instanced_scene> instanced_;
};

// The entry points on the front surface (sheet-local mm) whose light, going along `inside` in the
// plate, meets `faces` in this order (reflecting at each): the intersection of each face's
// outline traced back to the front surface. `faces`: the face and the sheet-local origin of its
// cell, as the walk met them.
polygon2 tile_path_aperture(const tile_sheet_geometry& g, const tile_structure& t, const glm::dvec3& inside,
                            const std::vector<std::pair<int, glm::dvec3>>& faces);

// Light arriving against wi (sheet-local, wi.z > 0) at `entry` (mm) on the front surface, as
// trace_prism_sheet.
prism_path trace_tile_sheet(const tile_sheet_geometry& g, const tile_structure& t, const glm::dvec3& wi,
                            const glm::dvec2& entry, double u_front, pcg32& rng);

// The tile sheet as a retroreflector model: a sample enters at a point of the cell drawn from
// u.lobe, the front surface's choice takes u.shift.x, and the rest draws from u.more. Its kind is
// "tile_sheet".
class tile_sheet_retro final : public retro_model {
 public:
  explicit tile_sheet_retro(const tile_sheet_geometry& g);  // throws input_error
  retro_sample sample(const glm::dvec3& wi, retro_samples u) const override;
  const tile_structure& structure() const { return *structure_; }

 private:
  tile_sheet_geometry g_;
  std::unique_ptr<tile_structure> structure_;
};

const retro_model_kind& tile_sheet_retro_kind();

}  // namespace airr
