// The Phong lighting kernels behind drawMesh3d's lit shading (lighting_kernel.hpp): each build
// (SSE2 baseline, AVX2) against the model written out in double here, and the builds against each
// other bit for bit, so that an image does not depend on the CPU that drew it.
#include "../modules/shading/src/lighting_kernel.hpp"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

namespace {

using cv::shading::detail::KernelBuild;
using cv::shading::detail::kLightBatch;
using cv::shading::detail::lightBatchWith;
using cv::shading::detail::LightingKernel;

struct Case {
    std::vector<float> positions, intensities;  // 3 per light
    LightingKernel kernel;
    float in[9][kLightBatch];
};

//! A random lighting and batch: `lights` lights, colours in units of `unit`, `shininess`.
Case makeCase(cv::RNG& rng, int lights, double shininess, float unit)
{
    Case c;
    for (int i = 0; i < lights; i++)
        for (int k = 0; k < 3; k++) {
            c.positions.push_back(float(rng.uniform(-4.0, 4.0)));
            c.intensities.push_back(float(rng.uniform(0.0, 1.0)));
        }
    LightingKernel& k = c.kernel;
    k.lightPositions = c.positions.data();
    k.lightIntensities = c.intensities.data();
    k.lightCount = lights;
    for (int j = 0; j < 3; j++) {
        k.eye[j] = float(rng.uniform(-4.0, 4.0));
        k.ambient[j] = float(rng.uniform(0.0, 0.3));
    }
    k.kd = float(rng.uniform(0.0, 1.0));
    k.ks = float(rng.uniform(0.0, 1.0));
    k.shininess = shininess;
    k.wholeShininess =
        shininess == std::floor(shininess) && shininess <= 256 ? int(shininess) : -1;
    k.toColor = 1.f / unit;
    k.toUnit = unit;
    for (int i = 0; i < kLightBatch; i++) {
        for (int j = 0; j < 3; j++) {
            c.in[j][i] = float(rng.uniform(-2.0, 2.0));
            c.in[6 + j][i] = float(rng.uniform(0.0, 1.0)) * unit;
        }
        // Unit normals, some zero (ambient only).
        double n[3] = {rng.gaussian(1), rng.gaussian(1), rng.gaussian(1)};
        const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        const bool zero = i % 13 == 5;
        for (int j = 0; j < 3; j++)
            c.in[3 + j][i] = zero ? 0.f : float(n[j] / length);
    }
    return c;
}

/** The model in double, sample i: I = c (Ia ka + kd sum I_i max(N.L_i, 0)) + ks sum I_i
[N.L_i > 0] max(R_i.V, 0)^shininess, clamped to [0, 1], in units. `nearEdge` is set when a
[N.L > 0] or [R.V > 0] decision is within float rounding of its edge. */
void reference(const Case& c, int i, double out[3], bool& nearEdge)
{
    const LightingKernel& k = c.kernel;
    double p[3], n[3], v[3];
    for (int j = 0; j < 3; j++) {
        p[j] = c.in[j][i];
        n[j] = c.in[3 + j][i];
        v[j] = k.eye[j] - p[j];
    }
    auto normalize = [](double* x) {
        const double length = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        for (int j = 0; j < 3; j++)
            x[j] = length > 0 ? x[j] / length : 0.0;
    };
    normalize(n);
    normalize(v);
    double diffuse[3], specular[3] = {0, 0, 0};
    for (int j = 0; j < 3; j++)
        diffuse[j] = k.ambient[j];
    nearEdge = false;
    for (int light = 0; light < k.lightCount; light++) {
        double l[3];
        for (int j = 0; j < 3; j++)
            l[j] = k.lightPositions[3 * light + j] - p[j];
        normalize(l);
        const double nl = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
        nearEdge |= std::abs(nl) < 1e-4;
        if (nl <= 0)
            continue;
        double rv = 0;
        for (int j = 0; j < 3; j++)
            rv += (2 * nl * n[j] - l[j]) * v[j];
        nearEdge |= std::abs(rv) < 1e-4;
        for (int j = 0; j < 3; j++) {
            const double intensity = k.lightIntensities[3 * light + j];
            diffuse[j] += intensity * k.kd * nl;
            if (rv > 0)
                specular[j] += intensity * k.ks * std::pow(rv, k.shininess);
        }
    }
    for (int j = 0; j < 3; j++) {
        const double color = c.in[6 + j][i] / k.toUnit;
        out[j] = std::min(std::max(color * diffuse[j] + specular[j], 0.0), 1.0) * k.toUnit;
    }
}

TEST(LightingKernel, EachBuildMatchesTheModelInDouble)
{
    cv::RNG rng(20261124);
    for (KernelBuild build : {KernelBuild::kBaseline, KernelBuild::kAvx2}) {
        bool ran = false;
        int checked = 0;
        for (int lights = 0; lights <= 4; lights++)
            for (double shininess : {0.0, 1.0, 7.0, 32.0, 256.0, 0.5, 13.3, 300.0})
                for (float unit : {1.f, 255.f}) {
                    Case c = makeCase(rng, lights, shininess, unit);
                    float out[3][kLightBatch];
                    if (!lightBatchWith(build, false, c.kernel, c.in, out, kLightBatch))
                        continue;  // not built, or not this CPU
                    ran = true;
                    for (int i = 0; i < kLightBatch; i++) {
                        double expected[3];
                        bool nearEdge;
                        reference(c, i, expected, nearEdge);
                        if (nearEdge)
                            continue;
                        for (int j = 0; j < 3; j++)
                            ASSERT_NEAR(out[j][i], expected[j], 2e-4 * unit)
                                << "build " << int(build) << ", " << lights << " lights, "
                                << "shininess " << shininess << ", sample " << i;
                        checked++;
                    }
                }
        // The baseline is always there; of 5,120 samples, those left are within rounding of
        // an edge.
        EXPECT_TRUE(ran || build == KernelBuild::kAvx2);
        if (ran) {
            EXPECT_GT(checked, 4500) << "build " << int(build);
        }
    }
}

TEST(LightingKernel, BuildsAgreeBitForBit)
{
    cv::RNG rng(7);
    for (int lights = 0; lights <= 4; lights++)
        for (double shininess : {0.0, 1.0, 32.0, 100.0, 13.3})
            for (bool terms : {false, true}) {
                Case c = makeCase(rng, lights, shininess, 1.f);
                float base[6][kLightBatch], avx2[6][kLightBatch];
                ASSERT_TRUE(lightBatchWith(KernelBuild::kBaseline, terms, c.kernel, c.in, base,
                                           kLightBatch));
                if (!lightBatchWith(KernelBuild::kAvx2, terms, c.kernel, c.in, avx2,
                                    kLightBatch))
                    GTEST_SKIP() << "no AVX2 build, or a CPU without AVX2";
                const int rows = terms ? 6 : 3;
                for (int j = 0; j < rows; j++)
                    ASSERT_EQ(std::memcmp(base[j], avx2[j], sizeof(base[j])), 0)
                        << "row " << j << ", " << lights << " lights, shininess " << shininess;
            }
}

}  // namespace
