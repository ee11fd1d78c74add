// Reflectance models of the synthetic rig: Lambertian, Blinn-Phong, Ward anisotropic and Ashikhmin-Shirley
// anisotropic BRDFs, all reciprocal (f(wi, wo) = f(wo, wi)) and with directional albedo <= 1 for valid parameters.
#pragma once

#include <string>

#include <Eigen/Core>

namespace rfrecon::sim {

enum class BrdfModel { kLambert, kBlinnPhong, kWard, kAshikhminShirley };

const char* to_string(BrdfModel model);
BrdfModel brdf_model_from_string(const std::string& name);  // throws InputError

// Parameters of every model; each model reads the ones listed next to it.
struct Brdf {
  BrdfModel model = BrdfModel::kLambert;
  double diffuse = 0.5;    // all: diffuse albedo rho_d (Ashikhmin-Shirley: R_d)
  double specular = 0.0;   // Blinn-Phong k_s, Ward rho_s, Ashikhmin-Shirley R_s (normal-incidence reflectance)
  double exponent = 50.0;  // Blinn-Phong: exponent of (n.h)
  double alpha_x = 0.1;    // Ward: roughness along the tangent (brushing) direction
  double alpha_y = 0.1;    // Ward: roughness across it
  double n_u = 100.0;      // Ashikhmin-Shirley: exponent along the tangent
  double n_v = 100.0;      // Ashikhmin-Shirley: exponent across it
};

// Throws InputError naming `field` (e.g. "objects[0].material") when a parameter is out of range; the ranges keep the
// directional albedo <= 1 (diffuse + specular <= 1, roughnesses and exponents > 0).
void validate(const Brdf& brdf, const std::string& field);

// f_r in 1/sr for unit directions in the local shading frame (x = tangent, y = bitangent, z = normal), both pointing
// away from the surface. Zero when either direction is below the surface. `diffuse` replaces brdf.diffuse (textures).
double evaluate(const Brdf& brdf, double diffuse, const Eigen::Vector3d& wi, const Eigen::Vector3d& wo);
inline double evaluate(const Brdf& brdf, const Eigen::Vector3d& wi, const Eigen::Vector3d& wo) {
  return evaluate(brdf, brdf.diffuse, wi, wo);
}

}  // namespace rfrecon::sim
