// This file is part of opencv_shading. License: Apache-2.0.
//
// perf_llvmpipe3d.hpp: the 3D scenes (perf_render3d.hpp) drawn by Mesa's llvmpipe through OSMesa,
// with shaders computing drawMesh3d's lighting formula, so both do the same work per frame:
//
//   llvmpipe/SCENE/SHADE/VIS/threads:N  clear to white (and the depth buffer for the z-buffer),
//                                       draw the mesh, glFinish
//
// An OpenGL 3.3 core profile context (GLSL 330), one per scene, uniforms set once. The mesh is
// in vertex and index buffers uploaded once; only painter's face order is sorted on the CPU and
// re-uploaded each frame (a radix sort by decreasing mean camera z, ties in face order, as
// drawMesh3d orders them). The z-buffer is GL_LESS on a 24-bit depth buffer, painter's draws
// with the depth test off. Lighting is in world space, as in mesh3d.hpp:
//   flat     lit once per face, in the vertex shader of the face's provoking (first) vertex,
//            which carries the face's centroid, normal and mean colour (a `flat` varying);
//            the faces' other corners are shared position-only vertices
//   gouraud  lit per vertex in the vertex shader, interpolated (perspective-correct)
//   phong    world position, normal and colour interpolated, the normal renormalized and lit
//            per fragment
// The camera is the scene's K, R, t: clip = P [R t] X, where P maps pixel (u, v) (centres at
// integers) to the window point (u + 1/2, v + 1/2) and v to GL's window y unflipped, since
// OSMESA_Y_UP makes window row y canvas row y (y down in the canvas, as OpenCV's). The canvas is
// OSMesa's float RGBA buffer; alpha is 0 where nothing was drawn (the coverage the check uses).
//
// addLlvmpipe3dBenchmarks checks each scene once, untimed, against drawMesh3d (pixels covered
// by one but not the other, mean colour difference) and leaves out a scene's llvmpipe cells when
// the images differ grossly (a bug in this peer).
//
// The textured variant (llvmpipeTextured/SCENE/SHADE/VIS/threads:N, a context of its own per
// scene, addLlvmpipeTextured3dBenchmarks) draws the scene of makeTexturedScene3d as
// drawTexturedMesh3d does, with the texel in the vertex colour's place in the lighting split
// I = c D + S (D ambient and diffuse factor, S highlight):
//   flat     D and S once per face in the provoking vertex (flat varyings), the texture
//            coordinate interpolated; each fragment writes clamp(texel D + S)
//   gouraud  D and S per vertex, interpolated (perspective-correct); clamp(texel D + S)
//   phong    D and S per fragment at the interpolated position and renormalized normal
// The texture is the scene's 8-bit one as GL_RGBA8 (texel values k/255, as the library's float
// texture holds them), GL_LINEAR both ways without mipmaps, GL_REPEAT (BORDER_WRAP), bound once.
// Rows are uploaded top-down, so texture pixel (u, v) (centres at integers, (0, 0) the top-left
// texel) is GL's (s, t) = ((u + 1/2) / cols, (v + 1/2) / rows), computed per vertex on the CPU.
// The check against drawTexturedMesh3d also gives the share of pixels off by more than 1/255:
// remap's bilinear weights are in 1/32 texel, llvmpipe's 8-bit filtering has its own rounding.
#ifndef OPENCV_SHADING_PERF_LLVMPIPE3D_HPP
#define OPENCV_SHADING_PERF_LLVMPIPE3D_HPP

#ifndef GL_GLEXT_PROTOTYPES
#error "perf_llvmpipe3d.hpp needs GL_GLEXT_PROTOTYPES defined before any GL header (CMake does)"
#endif

#include "perf_harness.hpp"
#include "perf_render3d.hpp"

#include <GL/osmesa.h>
#include <GL/glext.h>

#include <opencv2/core.hpp>
#include <opencv2/shading.hpp>

#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace shading_perf {

namespace gl3d {

// drawMesh3d's lighting (mesh3d.hpp), per channel and clamped; NUM_LIGHTS is #defined.
constexpr const char* kLighting = R"(
uniform vec3 eye;
uniform vec3 lightPos[NUM_LIGHTS];
uniform vec3 lightIntensity[NUM_LIGHTS];
uniform vec3 ambient;  // ka * Ia
uniform float kd, ks, shininess;

vec3 shade(vec3 P, vec3 N, vec3 c)
{
    vec3 V = normalize(eye - P);
    vec3 diffuse = vec3(0.0), specular = vec3(0.0);
    for (int i = 0; i < NUM_LIGHTS; ++i) {
        vec3 L = normalize(lightPos[i] - P);
        float nl = dot(N, L);
        vec3 R = 2.0 * nl * N - L;
        diffuse += lightIntensity[i] * max(nl, 0.0);
        specular += lightIntensity[i] * (nl > 0.0 ? pow(max(dot(R, V), 0.0), shininess) : 0.0);
    }
    return clamp(c * (ambient + kd * diffuse) + ks * specular, 0.0, 1.0);
}
)";

constexpr const char* kFlatVertex = R"(
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 faceCentroid;  // ("centroid" is a GLSL keyword)
layout(location = 2) in vec3 normal;
layout(location = 3) in vec3 color;
uniform mat4 mvp;
uniform int faceCount;
flat out vec3 faceColor;
void main()
{
    gl_Position = mvp * vec4(position, 1.0);
    // Vertices 0 .. faceCount-1 provoke one face each; the others only place corners.
    faceColor = gl_VertexID < faceCount ? shade(faceCentroid, normal, color) : vec3(0.0);
}
)";

constexpr const char* kFlatFragment = R"(
flat in vec3 faceColor;
out vec4 fragColor;
void main() { fragColor = vec4(faceColor, 1.0); }
)";

constexpr const char* kGouraudVertex = R"(
layout(location = 0) in vec3 position;
layout(location = 2) in vec3 normal;
layout(location = 3) in vec3 color;
uniform mat4 mvp;
out vec3 vertexColor;
void main()
{
    gl_Position = mvp * vec4(position, 1.0);
    vertexColor = shade(position, normal, color);
}
)";

constexpr const char* kGouraudFragment = R"(
in vec3 vertexColor;
out vec4 fragColor;
void main() { fragColor = vec4(vertexColor, 1.0); }
)";

constexpr const char* kPhongVertex = R"(
layout(location = 0) in vec3 position;
layout(location = 2) in vec3 normal;
layout(location = 3) in vec3 color;
uniform mat4 mvp;
out vec3 worldPosition, worldNormal, vertexColor;
void main()
{
    gl_Position = mvp * vec4(position, 1.0);
    worldPosition = position;
    worldNormal = normal;
    vertexColor = color;
}
)";

constexpr const char* kPhongFragment = R"(
in vec3 worldPosition, worldNormal, vertexColor;
out vec4 fragColor;
void main()
{
    // A zero normal gets the ambient term only, as in drawMesh3d.
    float len2 = dot(worldNormal, worldNormal);
    vec3 N = len2 > 0.0 ? worldNormal * inversesqrt(len2) : vec3(0.0);
    fragColor = vec4(shade(worldPosition, N, vertexColor), 1.0);
}
)";

// The textured programs' lighting: drawMesh3d's model split as I = c D + S (before the clamp),
// as drawTexturedMesh3d splits it; shade() above is clamp(c D + S) with these D and S.
constexpr const char* kLightingTerms = R"(
uniform vec3 eye;
uniform vec3 lightPos[NUM_LIGHTS];
uniform vec3 lightIntensity[NUM_LIGHTS];
uniform vec3 ambient;  // ka * Ia
uniform float kd, ks, shininess;

void terms(vec3 P, vec3 N, out vec3 D, out vec3 S)
{
    vec3 V = normalize(eye - P);
    vec3 diffuse = vec3(0.0), specular = vec3(0.0);
    for (int i = 0; i < NUM_LIGHTS; ++i) {
        vec3 L = normalize(lightPos[i] - P);
        float nl = dot(N, L);
        vec3 R = 2.0 * nl * N - L;
        diffuse += lightIntensity[i] * max(nl, 0.0);
        specular += lightIntensity[i] * (nl > 0.0 ? pow(max(dot(R, V), 0.0), shininess) : 0.0);
    }
    D = ambient + kd * diffuse;
    S = ks * specular;
}
)";

constexpr const char* kTexturedFlatVertex = R"(
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 faceCentroid;
layout(location = 2) in vec3 normal;
layout(location = 3) in vec2 texCoord;  // GL's (s, t)
uniform mat4 mvp;
uniform int faceCount;
flat out vec3 faceD, faceS;
out vec2 uv;
void main()
{
    gl_Position = mvp * vec4(position, 1.0);
    uv = texCoord;
    // Vertices 0 .. faceCount-1 provoke one face each; the others place corners.
    if (gl_VertexID < faceCount) {
        terms(faceCentroid, normal, faceD, faceS);
    } else {
        faceD = vec3(0.0);
        faceS = vec3(0.0);
    }
}
)";

constexpr const char* kTexturedFlatFragment = R"(
flat in vec3 faceD, faceS;
in vec2 uv;
uniform sampler2D tex;
out vec4 fragColor;
void main() { fragColor = vec4(clamp(texture(tex, uv).rgb * faceD + faceS, 0.0, 1.0), 1.0); }
)";

constexpr const char* kTexturedGouraudVertex = R"(
layout(location = 0) in vec3 position;
layout(location = 2) in vec3 normal;
layout(location = 3) in vec2 texCoord;
uniform mat4 mvp;
out vec3 vertexD, vertexS;
out vec2 uv;
void main()
{
    gl_Position = mvp * vec4(position, 1.0);
    uv = texCoord;
    terms(position, normal, vertexD, vertexS);
}
)";

constexpr const char* kTexturedGouraudFragment = R"(
in vec3 vertexD, vertexS;
in vec2 uv;
uniform sampler2D tex;
out vec4 fragColor;
void main() { fragColor = vec4(clamp(texture(tex, uv).rgb * vertexD + vertexS, 0.0, 1.0), 1.0); }
)";

constexpr const char* kTexturedPhongVertex = R"(
layout(location = 0) in vec3 position;
layout(location = 2) in vec3 normal;
layout(location = 3) in vec2 texCoord;
uniform mat4 mvp;
out vec3 worldPosition, worldNormal;
out vec2 uv;
void main()
{
    gl_Position = mvp * vec4(position, 1.0);
    worldPosition = position;
    worldNormal = normal;
    uv = texCoord;
}
)";

constexpr const char* kTexturedPhongFragment = R"(
in vec3 worldPosition, worldNormal;
in vec2 uv;
uniform sampler2D tex;
out vec4 fragColor;
void main()
{
    float len2 = dot(worldNormal, worldNormal);
    vec3 N = len2 > 0.0 ? worldNormal * inversesqrt(len2) : vec3(0.0);
    vec3 D, S;
    terms(worldPosition, N, D, S);
    fragColor = vec4(clamp(texture(tex, uv).rgb * D + S, 0.0, 1.0), 1.0);
}
)";

inline GLuint compileShader(GLenum type, const std::string& source)
{
    const GLuint shader = glCreateShader(type);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096] = {};
        glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
        throw std::runtime_error(std::string("llvmpipe3d: shader does not compile: ") + log);
    }
    return shader;
}

//! A program of `vertex` and `fragment`, each after `lighting` (kLighting or kLightingTerms).
inline GLuint linkProgram(const char* vertex, const char* fragment, int lights,
                          const char* lighting = kLighting)
{
    const std::string header = "#version 330 core\n#define NUM_LIGHTS " +
                               std::to_string(lights) + "\n";
    const GLuint vs = compileShader(GL_VERTEX_SHADER, header + lighting + vertex);
    const GLuint fs = compileShader(GL_FRAGMENT_SHADER, header + lighting + fragment);
    const GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096] = {};
        glGetProgramInfoLog(program, sizeof(log), nullptr, log);
        throw std::runtime_error(std::string("llvmpipe3d: program does not link: ") + log);
    }
    return program;
}

inline void checkError(const char* where)
{
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR)
        throw std::runtime_error(std::string("llvmpipe3d: GL error ") + std::to_string(error) +
                                 " " + where);
}

// Float -> unsigned key, larger float -> smaller key (decreasing order when sorted ascending).
inline uint32_t descendingKey(float x)
{
    uint32_t bits;
    std::memcpy(&bits, &x, sizeof(bits));
    bits = (bits & 0x80000000u) ? ~bits : bits | 0x80000000u;  // ascending with x
    return ~bits;
}

}  // namespace gl3d

//! One OSMesa context drawing one 3D scene, or one textured 3D scene, into float RGBA canvases.
class Llvmpipe3d {
public:
    //! The scene with its vertex colours (drawMesh3d's image).
    explicit Llvmpipe3d(const Scene3d& sc) : Llvmpipe3d(sc, nullptr) {}
    //! The textured scene (drawTexturedMesh3d's image, bilinear, BORDER_WRAP).
    explicit Llvmpipe3d(const TexturedScene3d& ts) : Llvmpipe3d(ts.scene, &ts) {}
    ~Llvmpipe3d() { OSMesaDestroyContext(context_); }  // frees the GL objects with it
    Llvmpipe3d(const Llvmpipe3d&) = delete;
    Llvmpipe3d& operator=(const Llvmpipe3d&) = delete;

    //! The GL_VERSION string of the context.
    const std::string& version() const { return version_; }

    //! One frame into `canvas` (made CV_32FC4 of the scene's size and bound if needed).
    void render(int shade, int visibility, cv::Mat& canvas)
    {
        bindIfNeeded(canvas);
        const bool zbuffer = visibility == cv::shading::VISIBILITY_ZBUFFER;
        const bool flat = shade == cv::shading::SHADE_FLAT;
        const int program = shade == cv::shading::SHADE_FLAT ? 0
                            : shade == cv::shading::SHADE_GOURAUD ? 1 : 2;
        if (currentProgram_ != program) {
            glUseProgram(programs_[program]);
            currentProgram_ = program;
        }
        if (depthTest_ != zbuffer) {
            if (zbuffer)
                glEnable(GL_DEPTH_TEST);
            else
                glDisable(GL_DEPTH_TEST);
            depthTest_ = zbuffer;
        }
        glClear(zbuffer ? GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT : GL_COLOR_BUFFER_BIT);
        const int vao = (flat ? 0 : 2) + (zbuffer ? 0 : 1);
        if (currentVao_ != vao) {
            glBindVertexArray(vaos_[vao]);
            currentVao_ = vao;
        }
        if (!zbuffer) {
            sortFaces(flat);
            glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0,
                            GLsizeiptr(indices_.size() * sizeof(GLuint)), indices_.data());
        }
        glDrawElements(GL_TRIANGLES, GLsizei(3 * faceCount_), GL_UNSIGNED_INT, nullptr);
        glFinish();  // the image is in `canvas` after this
    }

private:
    Llvmpipe3d(const Scene3d& sc, const TexturedScene3d* textured)
        : scene_(sc), textured_(textured)
    {
        const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                                  OSMESA_STENCIL_BITS, 0, OSMESA_ACCUM_BITS, 0,
                                  OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                                  OSMESA_CONTEXT_MAJOR_VERSION, 3,
                                  OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
        context_ = OSMesaCreateContextAttribs(attributes, nullptr);
        if (context_ == nullptr)
            throw std::runtime_error("OSMesaCreateContextAttribs (3.3 core) failed");
        try {
            scratch_.create(1, 1, CV_32FC4);  // for setting up; canvases are bound later
            if (!OSMesaMakeCurrent(context_, scratch_.data, GL_FLOAT, 1, 1))
                throw std::runtime_error("OSMesaMakeCurrent failed");
            version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
            setUp();
        } catch (...) {
            OSMesaDestroyContext(context_);  // no destructor runs for a half-built object
            throw;
        }
    }

    // Makes `canvas` (made the scene's size, CV_32FC4) this context's colour buffer, current,
    // unless it is already: pixel (x, y) is canvas row y, OSMesa's window row y.
    void bindIfNeeded(cv::Mat& canvas)
    {
        const cv::Size size = scene_.size;
        if (canvas.size() == size && canvas.type() == CV_32FC4 && canvas.data == bound_ &&
            OSMesaGetCurrentContext() == context_)
            return;  // (another context may have been made current meanwhile)
        canvas.create(size, CV_32FC4);
        bound_ = canvas.data;
        if (!OSMesaMakeCurrent(context_, canvas.data, GL_FLOAT, size.width, size.height))
            throw std::runtime_error("OSMesaMakeCurrent failed");
        OSMesaPixelStore(OSMESA_Y_UP, 1);
        glViewport(0, 0, size.width, size.height);
    }

    // Programs, buffers and uniforms: everything but the painter's index order, once.
    void setUp()
    {
        const Mesh3d& m = scene_.mesh;
        faceCount_ = m.faces.rows;
        vertexCount_ = m.verts3d.rows;
        const int lights = int(scene_.settings.lights.size());
        if (textured_ == nullptr) {
            programs_[0] = gl3d::linkProgram(gl3d::kFlatVertex, gl3d::kFlatFragment, lights);
            programs_[1] = gl3d::linkProgram(gl3d::kGouraudVertex, gl3d::kGouraudFragment,
                                             lights);
            programs_[2] = gl3d::linkProgram(gl3d::kPhongVertex, gl3d::kPhongFragment, lights);
        } else {
            programs_[0] = gl3d::linkProgram(gl3d::kTexturedFlatVertex,
                                             gl3d::kTexturedFlatFragment, lights,
                                             gl3d::kLightingTerms);
            programs_[1] = gl3d::linkProgram(gl3d::kTexturedGouraudVertex,
                                             gl3d::kTexturedGouraudFragment, lights,
                                             gl3d::kLightingTerms);
            programs_[2] = gl3d::linkProgram(gl3d::kTexturedPhongVertex,
                                             gl3d::kTexturedPhongFragment, lights,
                                             gl3d::kLightingTerms);
        }
        const cv::Matx44f mvp = modelViewProjection();
        const cv::shading::RenderSettings& s = scene_.settings;
        std::vector<cv::Vec3f> lightPos, lightIntensity;
        for (const cv::shading::PointLight& light : s.lights) {
            lightPos.emplace_back(cv::Vec3d(light.position));
            lightIntensity.emplace_back(light.intensity);
        }
        const cv::Vec3f ambient(s.ambient * s.ka), eye(scene_.eye);
        for (GLuint program : programs_) {
            glUseProgram(program);
            glUniformMatrix4fv(glGetUniformLocation(program, "mvp"), 1, GL_TRUE, mvp.val);
            glUniform3fv(glGetUniformLocation(program, "eye"), 1, eye.val);
            glUniform3fv(glGetUniformLocation(program, "lightPos"), lights, lightPos[0].val);
            glUniform3fv(glGetUniformLocation(program, "lightIntensity"), lights,
                         lightIntensity[0].val);
            glUniform3fv(glGetUniformLocation(program, "ambient"), 1, ambient.val);
            glUniform1f(glGetUniformLocation(program, "kd"), float(s.kd));
            glUniform1f(glGetUniformLocation(program, "ks"), float(s.ks));
            glUniform1f(glGetUniformLocation(program, "shininess"), float(s.shininess));
            glUniform1i(glGetUniformLocation(program, "faceCount"), faceCount_);  // flat only
            if (textured_ != nullptr)
                glUniform1i(glGetUniformLocation(program, "tex"), 0);  // texture unit 0
        }
        glUseProgram(0);

        // Flat: faceCount_ provoking vertices (corner 0, centroid, face normal, mean colour or
        // corner 0's texture coordinate), then the shared vertices (position, and the texture
        // coordinate when textured). Smooth: position, vertex normal, colour or texture
        // coordinate. Colours have 3 floats, GL texture coordinates (s, t) 2.
        const int last = textured_ != nullptr ? 2 : 3;  // floats of the last attribute
        const int flatStride = 9 + last, smoothStride = 6 + last;
        // Per vertex, the colour or (s, t, 0).
        std::vector<cv::Vec3f> lastAttribute(static_cast<size_t>(vertexCount_));
        for (int v = 0; v < vertexCount_; ++v) {
            if (textured_ == nullptr) {
                lastAttribute[v] = m.vcolors.at<cv::Vec3f>(v);
            } else {
                const cv::Vec2f uv = textured_->texCoords.at<cv::Vec2f>(v);
                const cv::Size texSize = textured_->texture8u.size();
                lastAttribute[v] = cv::Vec3f(float((double(uv[0]) + 0.5) / texSize.width),
                                             float((double(uv[1]) + 0.5) / texSize.height), 0.f);
            }
        }
        std::vector<float> flatVertices(size_t(faceCount_ + vertexCount_) * flatStride, 0.f);
        for (int f = 0; f < faceCount_; ++f) {
            const cv::Vec3i& face = m.faces.at<cv::Vec3i>(f);
            cv::Vec3d p[3], centroid, color;
            for (int k = 0; k < 3; ++k) {
                p[k] = cv::Vec3d(m.verts3d.at<cv::Vec3f>(face[k]));
                centroid += p[k] / 3.0;
                if (textured_ == nullptr)
                    color += cv::Vec3d(m.vcolors.at<cv::Vec3f>(face[k])) / 3.0;
            }
            if (textured_ != nullptr)
                color = cv::Vec3d(lastAttribute[face[0]]);
            cv::Vec3d normal = (p[1] - p[0]).cross(p[2] - p[0]);
            const double length = cv::norm(normal);
            normal = length > 0 ? normal / length : cv::Vec3d();  // zero for a degenerate face
            const cv::Vec3d fields[4] = {p[0], centroid, normal, color};
            float* out = &flatVertices[size_t(f) * flatStride];
            for (int a = 0; a < 4; ++a)
                for (int k = 0; k < (a < 3 ? 3 : last); ++k)
                    out[3 * a + k] = float(fields[a][k]);
        }
        std::vector<float> smoothVertices(size_t(vertexCount_) * smoothStride);
        for (int v = 0; v < vertexCount_; ++v) {
            const cv::Vec3f fields[3] = {m.verts3d.at<cv::Vec3f>(v),
                                         m.normals.at<cv::Vec3f>(v), lastAttribute[v]};
            float* flatOut = &flatVertices[size_t(faceCount_ + v) * flatStride];
            std::memcpy(flatOut, fields[0].val, 3 * sizeof(float));
            if (textured_ != nullptr)
                std::memcpy(flatOut + 9, fields[2].val, 2 * sizeof(float));
            std::memcpy(&smoothVertices[size_t(v) * smoothStride], fields,
                        smoothStride * sizeof(float));
        }
        std::vector<GLuint> flatIndices, smoothIndices;
        for (int f = 0; f < faceCount_; ++f) {
            const cv::Vec3i& face = m.faces.at<cv::Vec3i>(f);
            flatIndices.insert(flatIndices.end(), {GLuint(f), GLuint(faceCount_ + face[1]),
                                                   GLuint(faceCount_ + face[2])});
            smoothIndices.insert(smoothIndices.end(),
                                 {GLuint(face[0]), GLuint(face[1]), GLuint(face[2])});
        }

        glGenBuffers(2, vbos_);
        glGenVertexArrays(4, vaos_);
        glGenBuffers(4, ebos_);
        for (int layout = 0; layout < 2; ++layout) {
            const bool flat = layout == 0;
            const std::vector<float>& vertices = flat ? flatVertices : smoothVertices;
            const std::vector<GLuint>& indices = flat ? flatIndices : smoothIndices;
            glBindBuffer(GL_ARRAY_BUFFER, vbos_[layout]);
            glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(float)),
                         vertices.data(), GL_STATIC_DRAW);
            for (int order = 0; order < 2; ++order) {  // 0: z-buffer, static; 1: painter's
                const int vao = 2 * layout + order;
                glBindVertexArray(vaos_[vao]);
                const GLsizei stride = GLsizei((flat ? flatStride : smoothStride) * sizeof(float));
                const GLuint locations[4] = {0, 1, 2, 3};
                for (int a = 0, offset = 0; a < 4; ++a) {
                    if (!flat && a == 1)
                        continue;  // no centroid
                    const int size = a < 3 ? 3 : last;
                    glEnableVertexAttribArray(locations[a]);
                    glVertexAttribPointer(locations[a], size, GL_FLOAT, GL_FALSE, stride,
                                          reinterpret_cast<const void*>(
                                              size_t(offset) * sizeof(float)));
                    offset += size;
                }
                glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebos_[vao]);
                glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(GLuint)),
                             indices.data(), order == 0 ? GL_STATIC_DRAW : GL_STREAM_DRAW);
            }
        }
        glBindVertexArray(0);
        currentVao_ = -1;
        if (textured_ != nullptr)
            uploadTexture();
        glProvokingVertex(GL_FIRST_VERTEX_CONVENTION);
        glDepthFunc(GL_LESS);
        glDisable(GL_DEPTH_TEST);
        depthTest_ = false;
        glDisable(GL_CULL_FACE);
        glDisable(GL_DITHER);
        glClearColor(1.f, 1.f, 1.f, 0.f);  // alpha 0: not covered
        glClearDepth(1.0);
        gl3d::checkError("after set-up");
    }

    /** The scene's 8-bit texture as GL_RGBA8 on texture unit 0, rows top-down (row 0 at t = 0):
    bilinear both ways, no mipmaps, GL_REPEAT. Bound for the context's life. */
    void uploadTexture()
    {
        cv::Mat rgba;
        cv::cvtColor(textured_->texture8u, rgba, cv::COLOR_RGB2RGBA);  // channel order kept
        glGenTextures(1, &texture_);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, texture_);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, int(rgba.step[0] / rgba.elemSize()));
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, rgba.cols, rgba.rows, 0, GL_RGBA,
                     GL_UNSIGNED_BYTE, rgba.data);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
        gl3d::checkError("uploading the texture");
    }

    /** P [R t]: camera coordinates (OpenCV's: x right, y down, z forward) to clip space, with
    window x = u + 1/2, window y = v + 1/2 for pixel coordinates (u, v), depth 0 at zNear and 1
    at zFar (twice the farthest vertex: beyond the mesh). */
    cv::Matx44f modelViewProjection() const
    {
        const cv::Matx33d& K = scene_.cameraMatrix;
        const cv::Matx33d& R = scene_.rotation;
        const cv::Vec3d t(scene_.tvec.ptr<double>());
        cv::Matx44d view = cv::Matx44d::eye();
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c)
                view(r, c) = R(r, c);
            view(r, 3) = t[r];
        }
        double farthest = 0;
        for (int v = 0; v < scene_.mesh.verts3d.rows; ++v) {
            const cv::Vec3d p(scene_.mesh.verts3d.at<cv::Vec3f>(v));
            farthest = std::max(farthest, R.row(2).dot(cv::Matx13d(p.val)) + t[2]);
        }
        const double w = scene_.size.width, h = scene_.size.height;
        const double n = scene_.settings.zNear, f = 2.0 * farthest;
        const cv::Matx44d projection(
            2 * K(0, 0) / w, 2 * K(0, 1) / w, 2 * (K(0, 2) + 0.5) / w - 1, 0,
            0, 2 * K(1, 1) / h, 2 * (K(1, 2) + 0.5) / h - 1, 0,
            0, 0, (f + n) / (f - n), -2 * f * n / (f - n),
            0, 0, 1, 0);
        return cv::Matx44f(projection * view);
    }

    /** Painter's order into indices_: faces by decreasing mean camera z (the sum of the three
    z), ties in face order: an LSD radix sort of (key, face) on the key's 32 bits, stable. */
    void sortFaces(bool flat)
    {
        const Mesh3d& m = scene_.mesh;
        const cv::Matx33d& R = scene_.rotation;
        const float r0 = float(R(2, 0)), r1 = float(R(2, 1)), r2 = float(R(2, 2)),
                    t2 = float(scene_.tvec.at<double>(2));
        depths_.resize(size_t(vertexCount_));
        const cv::Vec3f* verts = m.verts3d.ptr<cv::Vec3f>();
        for (int v = 0; v < vertexCount_; ++v)
            depths_[v] = r0 * verts[v][0] + r1 * verts[v][1] + r2 * verts[v][2] + t2;
        keys_.resize(size_t(faceCount_));
        scratch64_.resize(size_t(faceCount_));
        const cv::Vec3i* faces = m.faces.ptr<cv::Vec3i>();
        for (int f = 0; f < faceCount_; ++f) {
            const float sum = depths_[faces[f][0]] + depths_[faces[f][1]] + depths_[faces[f][2]];
            keys_[f] = uint64_t(gl3d::descendingKey(sum)) << 32 | uint32_t(f);
        }
        // Three passes of 11, 11 and 10 bits over the key (the high 32 bits).
        uint64_t* src = keys_.data();
        uint64_t* dst = scratch64_.data();
        for (int shift = 32; shift < 64; shift += 11) {
            size_t count[2048] = {};
            for (int f = 0; f < faceCount_; ++f)
                count[(src[f] >> shift) & 2047]++;
            size_t sum = 0;
            for (size_t& c : count) {
                const size_t here = c;
                c = sum;
                sum += here;
            }
            for (int f = 0; f < faceCount_; ++f)
                dst[count[(src[f] >> shift) & 2047]++] = src[f];
            std::swap(src, dst);
        }
        indices_.resize(3 * size_t(faceCount_));
        GLuint* out = indices_.data();
        for (int i = 0; i < faceCount_; ++i) {
            const int f = int(uint32_t(src[i]));
            *out++ = GLuint(flat ? f : faces[f][0]);
            *out++ = GLuint(flat ? faceCount_ + faces[f][1] : faces[f][1]);
            *out++ = GLuint(flat ? faceCount_ + faces[f][2] : faces[f][2]);
        }
    }

    const Scene3d& scene_;
    const TexturedScene3d* textured_ = nullptr;  // the textured scene, or null
    OSMesaContext context_ = nullptr;
    const uchar* bound_ = nullptr;  // the buffer the context draws into
    cv::Mat scratch_;               // bound while setting up
    std::string version_;
    int faceCount_ = 0, vertexCount_ = 0;
    GLuint programs_[3] = {};
    GLuint vbos_[2] = {};      // flat, smooth
    GLuint vaos_[4] = {};      // flat z-buffer, flat painter's, smooth z-buffer, smooth painter's
    GLuint ebos_[4] = {};      // their index buffers
    GLuint texture_ = 0;       // textured: the texture, on unit 0
    int currentProgram_ = -1, currentVao_ = -1;
    bool depthTest_ = false;
    std::vector<float> depths_;
    std::vector<uint64_t> keys_, scratch64_;
    std::vector<GLuint> indices_;
};

namespace gl3d {

//! The library's image of a cell, 1 thread: draw(shade, visibility, canvas, faceIds).
using LibraryImage = std::function<void(int, int, cv::Mat&, cv::Mat&)>;

/** Compares llvmpipe's images of `sc` with the library's (`draw`) for every shading and
visibility: the share of pixels whose coverage agrees and the mean absolute colour difference
(over all pixels and channels), and with `offShares` the share of the drawn pixels with a
channel off by more than 1/255 and by more than 8/255. Sets `ok` false when one is grossly off:
coverage agreeing on less than 99% of the pixels or a mean difference of 0.02 or more. */
inline std::string compareImages(const Scene3d& sc, const LibraryImage& draw, Llvmpipe3d& gl,
                                 bool offShares, bool& ok)
{
    ThreadCount scope(1);
    ok = true;
    std::string out;
    for (int shade : kShades3d) {
        for (int visibility : kVisibilities) {
            cv::Mat expected, faceIds, got;
            draw(shade, visibility, expected, faceIds);
            gl.render(shade, visibility, got);
            std::vector<cv::Mat> rgba;
            cv::split(got, rgba);
            const cv::Mat coveredGl = rgba[3] > 0.5f, coveredLib = faceIds >= 0;
            cv::Mat rgb, diff;
            cv::merge(std::vector<cv::Mat>(rgba.begin(), rgba.begin() + 3), rgb);
            cv::absdiff(expected, rgb, diff);
            const double pixels = double(sc.size.area());
            const double agree = 1.0 - cv::countNonZero(coveredGl != coveredLib) / pixels;
            const cv::Scalar sum = cv::sum(diff);
            const double meanDiff = (sum[0] + sum[1] + sum[2]) / (3.0 * pixels);
            double maxDiff = 0;
            cv::minMaxLoc(diff.reshape(1), nullptr, &maxDiff);
            ok = ok && agree > 0.99 && meanDiff < 0.02;
            char text[300];
            std::snprintf(text, sizeof(text),
                          "%s%s/%s: coverage agrees on %.3f%% of pixels (%d drawn, llvmpipe "
                          "%d), mean |diff| %.2g, max %.3f", out.empty() ? "" : "; ",
                          shadeName3d(shade), visibilityName(visibility), 100.0 * agree,
                          cv::countNonZero(coveredLib), cv::countNonZero(coveredGl), meanDiff,
                          maxDiff);
            out += text;
            if (offShares) {
                cv::Mat worst;  // per pixel, the largest channel difference
                cv::reduce(diff.reshape(1, sc.size.area()), worst, 1, cv::REDUCE_MAX);
                const double drawn = std::max(1, cv::countNonZero(coveredLib));
                std::snprintf(text, sizeof(text),
                              ", %.2f%% of drawn pixels off by more than 1/255, %.2f%% by more "
                              "than 8/255", 100.0 * cv::countNonZero(worst > 1.0 / 255) / drawn,
                              100.0 * cv::countNonZero(worst > 8.0 / 255) / drawn);
                out += text;
            }
        }
    }
    return out;
}

//! LP_NUM_THREADS, set to the number of CPUs unless set already (before the first context).
inline int llvmpipeThreads()
{
    const std::string cpus = std::to_string(cv::getNumberOfCPUs());
    setenv("LP_NUM_THREADS", cpus.c_str(), 0);  // kept if set
    return std::atoi(std::getenv("LP_NUM_THREADS"));
}

/** Registers METHOD/SCENE/SHADE/VIS/threads:N for `gl` on every shading and visibility, after
`check` (which sets ok): when it fails, no cells, and the context and stderr say so. */
inline void addCheckedCells(const std::string& method, const Scene3d& sc,
                            const std::string& checkName,
                            const std::function<std::shared_ptr<Llvmpipe3d>()>& make,
                            const std::function<std::string(Llvmpipe3d&, bool&)>& check)
{
    const int threads = llvmpipeThreads();
    std::shared_ptr<Llvmpipe3d> gl;
    bool ok = false;
    std::string result;
    try {
        gl = make();
        result = check(*gl, ok);
    } catch (const std::exception& e) {  // no 3.3 context, a shader error: no cells
        result = e.what();
    }
    benchmark::AddCustomContext(checkName + "/" + sc.name,
                                (ok ? "" : "FAILED, llvmpipe cells left out: ") + result);
    if (!ok) {
        std::cerr << checkName << " failed on " << sc.name << ": " << result << '\n';
        return;
    }
    benchmark::AddCustomContext("llvmpipe3d_gl_version", gl->version());
    for (int shade : kShades3d)
        for (int visibility : kVisibilities)
            addNamedBenchmark(cellName3d(method, sc, shade, visibility, threads),
                              sc.mesh.faces.rows, double(sc.size.area()), threads,
                              [gl, shade, visibility](cv::Mat& img) {
                                  gl->render(shade, visibility, img);
                              });
}

}  // namespace gl3d

/** Compares llvmpipe's images of `sc` with drawMesh3d's (1 thread) for every shading and
visibility: the share of pixels whose coverage agrees and the mean absolute colour difference
(over all pixels and channels). Sets `ok` false when one is grossly off: coverage agreeing on
less than 99% of the pixels or a mean difference of 0.02 or more. */
inline std::string compareWithDrawMesh3d(const Scene3d& sc, Llvmpipe3d& gl, bool& ok)
{
    return gl3d::compareImages(
        sc,
        [&sc](int shade, int visibility, cv::Mat& canvas, cv::Mat& faceIds) {
            cv::Mat depth;
            drawScene3d(sc, shade, visibility, canvas, depth, faceIds);
        },
        gl, false, ok);
}

/** The same against drawTexturedMesh3d (bilinear, BORDER_WRAP), with the shares of drawn
pixels off by more than 1/255 and 8/255. */
inline std::string compareWithDrawTexturedMesh3d(const TexturedScene3d& ts, Llvmpipe3d& gl,
                                                 bool& ok)
{
    return gl3d::compareImages(
        ts.scene,
        [&ts](int shade, int visibility, cv::Mat& canvas, cv::Mat& faceIds) {
            cv::Mat depth;
            drawTexturedScene3d(ts, shade, visibility, canvas, depth, faceIds);
        },
        gl, true, ok);
}

/** Registers llvmpipe on every 3D scene, each shading and visibility, with LP_NUM_THREADS
threads (set to the number of CPUs unless set already), after checking it against drawMesh3d:
a scene whose check fails gets no llvmpipe cells (the context says so). */
inline void addLlvmpipe3dBenchmarks(const std::vector<Scene3d>& scenes)
{
    for (const Scene3d& sc : scenes)
        gl3d::addCheckedCells(
            "llvmpipe", sc, "check_llvmpipe_vs_drawMesh3d",
            [&sc] { return std::make_shared<Llvmpipe3d>(sc); },
            [&sc](Llvmpipe3d& gl, bool& ok) { return compareWithDrawMesh3d(sc, gl, ok); });
}

/** llvmpipeTextured/SCENE/SHADE/VIS/threads:N on every textured 3D scene, as
addLlvmpipe3dBenchmarks, checked against drawTexturedMesh3d. */
inline void addLlvmpipeTextured3dBenchmarks(const std::vector<TexturedScene3d>& scenes)
{
    for (const TexturedScene3d& ts : scenes)
        gl3d::addCheckedCells(
            "llvmpipeTextured", ts.scene, "check_llvmpipe_vs_drawTexturedMesh3d",
            [&ts] { return std::make_shared<Llvmpipe3d>(ts); },
            [&ts](Llvmpipe3d& gl, bool& ok) { return compareWithDrawTexturedMesh3d(ts, gl, ok); });
}

}  // namespace shading_perf

#endif  // OPENCV_SHADING_PERF_LLVMPIPE3D_HPP
