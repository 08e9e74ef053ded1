// The variance of the sea surface's slopes along and across the wind: what the spectrum's
// moments give for a band of waves (Gamper A.1 in the wind frame, spectrum/moments.h), what a
// renderer leaves unresolved, and the roughness of the ocean BRDF (Bruneton 2010 eq. 4, whose
// σ_x², σ_y² are taken along the frame's T_x (upwind) and T_y (crosswind), shading/ocean_brdf.h).
#pragma once

namespace oceanref {

struct SlopeVariance {
  double upwind = 0.0;     // σ_x², along the wind
  double crosswind = 0.0;  // σ_y², across it
};

}  // namespace oceanref
