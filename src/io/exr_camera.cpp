#include "io/exr_camera.h"

#include "core/math.h"

namespace oceanref {

namespace {
using Matrix = std::array<std::array<double, 4>, 4>;

Matrix world_to_camera_double(const Camera& c) {
  Matrix m{};
  for (int axis = 0; axis < 3; ++axis) {
    const auto row = static_cast<std::size_t>(axis);
    m[row][0] = c.right[axis];
    m[row][1] = c.up[axis];
    m[row][2] = c.forward[axis];
  }
  m[3][0] = -glm::dot(c.position, c.right);
  m[3][1] = -glm::dot(c.position, c.up);
  m[3][2] = -glm::dot(c.position, c.forward);
  m[3][3] = 1.0;
  return m;
}

ExrMatrix to_float(const Matrix& m) {
  ExrMatrix f{};
  for (std::size_t r = 0; r < 4; ++r) {
    for (std::size_t c = 0; c < 4; ++c) f[r][c] = static_cast<float>(m[r][c]);
  }
  return f;
}
}  // namespace

ExrMatrix world_to_camera_matrix(const Camera& camera) {
  return to_float(world_to_camera_double(camera));
}

ExrMatrix world_to_ndc_matrix(const Camera& camera) {
  const double sy = 0.5 / math::tan(0.5 * camera.vertical_fov);
  const double sx = sy * camera.height / camera.width;
  const Matrix p{
      {{sx, 0.0, 0.0, 0.0}, {0.0, -sy, 0.0, 0.0}, {0.5, 0.5, 0.0, 1.0}, {0.0, 0.0, 1.0, 0.0}}};
  const Matrix v = world_to_camera_double(camera);
  Matrix m{};
  for (std::size_t r = 0; r < 4; ++r) {
    for (std::size_t c = 0; c < 4; ++c) {
      double sum = 0.0;
      for (std::size_t k = 0; k < 4; ++k) sum += v[r][k] * p[k][c];
      m[r][c] = sum;
    }
  }
  return to_float(m);
}

}  // namespace oceanref
