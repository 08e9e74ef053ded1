// A camera as the standard OpenEXR header attributes worldToCamera and worldToNDC
// (ImfStandardAttributes.h), so that another renderer can reproduce the view of an image.
//
// OpenEXR's matrices act on row vectors, p' = p·M (translation in row 3), with a projective
// divide by w for worldToNDC:
//   camera space: origin at the eye, +x right, +y up, +z along the viewing direction (left-handed,
//                 RenderMan's convention; objects in front of the camera have z > 0);
//   NDC:          (0, 0) the top-left and (1, 1) the bottom-right corner of the display window,
//                 y down; pixel (i, j) covers [i/W, (i+1)/W) × [j/H, (j+1)/H), as `project`.
#pragma once

#include "io/exr.h"
#include "raster/camera.h"

namespace oceanref {

ExrMatrix world_to_camera_matrix(const Camera& camera);
// worldToCamera · P with P mapping camera (x, y, z, 1) to (x s_x + z/2, −y s_y + z/2, 1, z),
// s_y = 1/(2 tan(fov_y/2)), s_x = s_y·H/W: NDC = (X/W, Y/W); the third coordinate, 1/z, is
// discarded by the standard.
ExrMatrix world_to_ndc_matrix(const Camera& camera);

}  // namespace oceanref
