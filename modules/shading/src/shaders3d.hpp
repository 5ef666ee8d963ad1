// This file is part of opencv_shading. License: Apache-2.0.
//
// Span shaders of the 3D path: perspective-correct depth and attributes, the z-buffer test, the
// depth and face-id outputs, and the Phong lighting model (seed 004) they share.
#ifndef OPENCV_SHADING_SHADERS3D_HPP
#define OPENCV_SHADING_SHADERS3D_HPP

#include "shaders.hpp"

#include <opencv2/core.hpp>

#include <cmath>
#include <vector>

namespace cv {
namespace shading {
namespace detail {

/** The Phong lighting model with the material, lights and eye of one drawMesh3d call:
I = c (ka Ia + kd sum I_i max(N.L_i, 0)) + ks sum I_i [N.L_i > 0] max(R_i.V, 0)^shininess, per
channel, clamped to [0, 1]. */
struct Lighting {
    struct Light {
        Vec3d position, intensity;
    };
    std::vector<Light> lights;  //!< empty: unlit
    Vec3d eye;                  //!< camera centre, world coordinates
    Vec3d ambient;              //!< ka Ia
    double kd = 0, ks = 0, shininess = 0;
    double unit = 1;            //!< the canvas's colour units per lighting unit (1 or 255)

    bool lit() const { return !lights.empty(); }

    /** The lit colour at world point p with normal n (unit, or zero: ambient only) and colour c,
    both colours in the canvas's units. */
    Vec3d shade(const Vec3d& p, const Vec3d& n, const Vec3d& color) const
    {
        const Vec3d c = color * (1.0 / unit);
        Vec3d diffuse = ambient, specular(0, 0, 0);
        const Vec3d toEye = eye - p;
        const double eyeLength = std::sqrt(toEye.dot(toEye));
        const Vec3d v = eyeLength > 0 ? toEye * (1.0 / eyeLength) : Vec3d(0, 0, 0);
        for (const Light& light : lights) {
            const Vec3d toLight = light.position - p;
            const double length = std::sqrt(toLight.dot(toLight));
            if (!(length > 0))
                continue;  // a light at the point lights no direction
            const Vec3d l = toLight * (1.0 / length);
            const double nl = n.dot(l);
            if (nl <= 0)
                continue;  // both terms vanish
            diffuse += light.intensity * (kd * nl);
            const Vec3d r = n * (2 * nl) - l;
            const double rv = r.dot(v);
            if (rv > 0)
                specular += light.intensity * (ks * std::pow(rv, shininess));
        }
        Vec3d out;
        for (int k = 0; k < 3; k++)
            out[k] = std::min(std::max(c[k] * diffuse[k] + specular[k], 0.0), 1.0) * unit;
        return out;
    }
};

//! Normalizes v; a zero (or non-finite-length) vector stays zero.
inline Vec3d unitOrZero(const Vec3d& v)
{
    const double length = std::sqrt(v.dot(v));
    return length > 0 && std::isfinite(length) ? v * (1.0 / length) : Vec3d(0, 0, 0);
}

/** What the 3D shaders write besides the canvas, and how they test. */
struct DepthTargets {
    uchar* depth = nullptr;  //!< CV_32FC1 rows, canvas-sized; null: not written
    size_t depthStep = 0;
    uchar* ids = nullptr;    //!< CV_32SC1 rows; null: not written
    size_t idsStep = 0;
    bool test = false;       //!< z-buffer: draw where depth < buffer, strictly
    const Lighting* lighting = nullptr;
};

/** Shades a triangle of the projected mesh. Per sample: the exact screen-space weights w_i,
their perspective-correct form q_i = (w_i / z_i) / sum_j (w_j / z_j) and the depth
1 / sum_j (w_j / z_j); then the z-buffer test, and the colour:
- kAttributes 0: a constant colour (flat);
- 3: the interpolated colour (Gouraud: vertex colours lit or as given);
- 9: interpolated world position, normal and colour, lit at the sample (Phong). */
template <typename T, int kAttributes>
struct SurfaceShader {
    ExactWeights weights;
    double invZ[3];                                  //!< 1 / Zc per vertex, canonical order
    double attributes[3][kAttributes ? kAttributes : 1];
    T color[3];                                      //!< kAttributes 0: the face's colour
    const DepthTargets* targets;
    int faceId;

    void operator()(const TriangleSetup& t, T* row, int y, int /*spanBegin*/, int xBegin,
                    int xEnd) const
    {
        const DepthTargets& out = *targets;
        float* const depthRow =
            out.depth ? reinterpret_cast<float*>(out.depth + size_t(y) * out.depthStep) : nullptr;
        int* const idRow =
            out.ids ? reinterpret_cast<int*>(out.ids + size_t(y) * out.idsStep) : nullptr;
        for (int x = xBegin; x < xEnd; x++) {
            double w0, w1, w2;
            weights.at(t, x, y, w0, w1, w2);
            const double q0 = w0 * invZ[0], q1 = w1 * invZ[1], q2 = w2 * invZ[2];
            const double sum = q0 + q1 + q2;
            const float depth = float(1.0 / sum);
            if (out.test && !(depth < depthRow[x]))
                continue;
            if (depthRow)
                depthRow[x] = depth;
            if (idRow)
                idRow[x] = faceId;
            T* pixel = row + 3 * x;
            if constexpr (kAttributes == 0) {
                pixel[0] = color[0], pixel[1] = color[1], pixel[2] = color[2];
            } else {
                const double inv = 1.0 / sum;
                double v[kAttributes];
                for (int k = 0; k < kAttributes; k++)
                    v[k] = (q0 * attributes[0][k] + q1 * attributes[1][k] +
                            q2 * attributes[2][k]) * inv;
                if constexpr (kAttributes == 9) {
                    const Vec3d c = out.lighting->shade(Vec3d(v[0], v[1], v[2]),
                                                        unitOrZero(Vec3d(v[3], v[4], v[5])),
                                                        Vec3d(v[6], v[7], v[8]));
                    for (int k = 0; k < 3; k++)
                        pixel[k] = toChannel<T>(float(c[k]));
                } else {
                    for (int k = 0; k < 3; k++)
                        pixel[k] = toChannel<T>(float(v[k]));
                }
            }
        }
    }
};

}  // namespace detail
}  // namespace shading
}  // namespace cv

#endif  // OPENCV_SHADING_SHADERS3D_HPP
