// This file is part of opencv_shading. License: Apache-2.0.
//
// loadMesh/saveMesh: mesh files through the Open Asset Import Library (assimp). The scene is
// flattened into the library's array form (one row per vertex or triangle).
#include "input.hpp"

#include <opencv2/shading.hpp>

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace cv {
namespace shading {

namespace {

std::string lowerExtension(const std::string& filename)
{
    std::string ext = std::filesystem::path(filename).extension().string();
    if (!ext.empty())
        ext.erase(0, 1);  // the dot
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

/** Stores `rows` (N x C, one item per row) into `out`: a Mat gets it as is; a fixed-type output
such as std::vector<Vec3f> or std::vector<Point3d> gets C-channel items of its own depth. */
void writeRows(const Mat& rows, OutputArray out, const char* argName)
{
    if (!out.needed())
        return;
    if (rows.empty()) {
        out.release();
        return;
    }
    Mat src = rows;
    int depth = rows.depth();
    if (out.fixedType()) {
        if (out.channels() == rows.cols)
            src = rows.reshape(rows.cols);
        else if (out.channels() != 1)
            CV_Error(Error::StsBadArg,
                     format("loadMesh: %s: an output of %d-channel items cannot hold %d values per "
                            "item", argName, out.channels(), rows.cols));
        depth = out.depth();
    }
    src.convertTo(out, depth);
}

void checkFinite(const std::vector<Vec3d>& items, const char* argName, int dims = 3)
{
    for (size_t i = 0; i < items.size(); i++)
        for (int k = 0; k < dims; k++)
            if (!std::isfinite(items[i][k]))
                CV_Error(Error::StsBadArg, format("saveMesh: %s: item %zu has a non-finite value "
                                                  "(%g)", argName, i, items[i][k]));
}

// Extension -> assimp export format id. OFF has no assimp exporter: written here. PLY is
// written as text: assimp 5.2 misreads some of its own binary PLY files.
const char* exportFormat(const std::string& ext)
{
    static const char* const table[][2] = {
        {"obj", "objnomtl"}, {"ply", "ply"}, {"stl", "stlb"},  {"gltf", "gltf2"},
        {"glb", "glb2"},     {"dae", "collada"}, {"fbx", "fbx"}, {"x3d", "x3d"},
        {"3mf", "3mf"},      {"x", "x"},        {"3ds", "3ds"}};
    for (const auto& row : table)
        if (ext == row[0])
            return row[1];
    return nullptr;
}

void writeOff(const std::string& filename, const std::vector<Vec3d>& vertices,
              const std::vector<Vec3i>& faces)
{
    std::ofstream f(filename);
    if (!f)
        CV_Error(Error::StsError, format("saveMesh: cannot open '%s' for writing",
                                         filename.c_str()));
    f.precision(9);  // enough digits to give every float back exactly
    f << "OFF\n" << vertices.size() << ' ' << faces.size() << " 0\n";
    for (const Vec3d& v : vertices)
        f << float(v[0]) << ' ' << float(v[1]) << ' ' << float(v[2]) << '\n';
    for (const Vec3i& t : faces)
        f << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
    f.close();
    if (!f)
        CV_Error(Error::StsError, format("saveMesh: writing '%s' failed", filename.c_str()));
}

}  // namespace

void loadMesh(const String& filename, OutputArray vertices, OutputArray faces, OutputArray normals,
              OutputArray colors, OutputArray texCoords)
{
    const char* file = filename.c_str();
    std::error_code ec;
    if (!std::filesystem::exists(filename, ec))
        CV_Error(Error::StsObjectNotFound, format("loadMesh: '%s' does not exist", file));
    if (std::filesystem::is_directory(filename, ec))
        CV_Error(Error::StsBadArg, format("loadMesh: '%s' is a folder, not a mesh file", file));

    Assimp::Importer importer;
    // ValidateDataStructure runs first and rejects broken indices before any other step reads
    // them; SortByPType splits points and lines off into meshes of their own, skipped below.
    const aiScene* scene = importer.ReadFile(
        filename, aiProcess_ValidateDataStructure | aiProcess_Triangulate |
                      aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices |
                      aiProcess_SortByPType);
    if (!scene)
        CV_Error(Error::StsParseError, format("loadMesh: cannot read '%s' as a mesh: %s", file,
                                              importer.GetErrorString()));

    std::vector<const aiMesh*> meshes;
    size_t vertexCount = 0, faceCount = 0;
    bool allNormals = true, allColors = true, allUV = true;
    int uvDims = 2;
    for (unsigned i = 0; i < scene->mNumMeshes; i++) {
        const aiMesh* m = scene->mMeshes[i];
        size_t triangles = 0;
        for (unsigned f = 0; f < m->mNumFaces; f++)
            triangles += m->mFaces[f].mNumIndices == 3;
        if (triangles == 0)
            continue;
        meshes.push_back(m);
        vertexCount += m->mNumVertices;
        faceCount += triangles;
        allNormals = allNormals && m->HasNormals();
        allColors = allColors && m->HasVertexColors(0);
        allUV = allUV && m->HasTextureCoords(0);
        if (m->HasTextureCoords(0) && m->mNumUVComponents[0] == 3)
            uvDims = 3;
    }
    if (faceCount == 0)
        CV_Error(Error::StsParseError,
                 format("loadMesh: '%s' holds no triangles (%u meshes, of points or lines only)",
                        file, scene->mNumMeshes));
    if (vertexCount > size_t(INT_MAX) || faceCount > size_t(INT_MAX))
        CV_Error(Error::StsOutOfRange,
                 format("loadMesh: '%s' has %zu vertices and %zu triangles, more than an int "
                        "index holds", file, vertexCount, faceCount));

    const int L = int(vertexCount), K = int(faceCount);
    Mat V(L, 3, CV_32F), F(K, 3, CV_32S), N, C, T;
    if (normals.needed() && allNormals)
        N.create(L, 3, CV_32F);
    if (colors.needed() && allColors)
        C.create(L, 3, CV_32F);
    if (texCoords.needed() && allUV)
        T.create(L, uvDims, CV_32F);

    int base = 0, face = 0;
    for (const aiMesh* m : meshes) {
        for (unsigned v = 0; v < m->mNumVertices; v++) {
            const int row = base + int(v);
            const aiVector3D& p = m->mVertices[v];
            float* dst = V.ptr<float>(row);
            dst[0] = p.x, dst[1] = p.y, dst[2] = p.z;
            if (!N.empty()) {
                const aiVector3D& n = m->mNormals[v];
                float* nd = N.ptr<float>(row);
                nd[0] = n.x, nd[1] = n.y, nd[2] = n.z;
            }
            if (!C.empty()) {
                const aiColor4D& c = m->mColors[0][v];
                float* cd = C.ptr<float>(row);
                cd[0] = c.r, cd[1] = c.g, cd[2] = c.b;
            }
            if (!T.empty()) {
                const aiVector3D& t = m->mTextureCoords[0][v];
                float* td = T.ptr<float>(row);
                td[0] = t.x, td[1] = t.y;
                if (uvDims == 3)  // 2-component sets of other meshes hold z = 0
                    td[2] = t.z;
            }
        }
        for (unsigned f = 0; f < m->mNumFaces; f++) {
            const aiFace& src = m->mFaces[f];
            if (src.mNumIndices != 3)
                continue;
            int* dst = F.ptr<int>(face++);
            for (int k = 0; k < 3; k++) {
                if (src.mIndices[k] >= m->mNumVertices)  // a broken file: never index past it
                    CV_Error(Error::StsParseError,
                             format("loadMesh: '%s': a face has vertex index %u, outside the "
                                    "%u vertices of its mesh", file, src.mIndices[k],
                                    m->mNumVertices));
                dst[k] = base + int(src.mIndices[k]);
            }
        }
        base += int(m->mNumVertices);
    }

    writeRows(V, vertices, "vertices");
    writeRows(F, faces, "faces");
    writeRows(N, normals, "normals");
    writeRows(C, colors, "colors");
    writeRows(T, texCoords, "texCoords");
}

void saveMesh(const String& filename, InputArray vertices, InputArray faces, InputArray normals,
              InputArray colors, InputArray texCoords)
{
    // Every argument is checked before anything is written.
    std::vector<Vec3d> V, N, C, T;
    std::vector<Vec3i> F;
    detail::readVectors(vertices, "vertices", -1, V);
    if (V.empty())
        CV_Error(Error::StsBadArg, "saveMesh: vertices: empty (a mesh needs at least one vertex)");
    checkFinite(V, "vertices");
    const int L = int(V.size());
    detail::readFaces(faces, "faces", L, F);
    if (F.empty())
        CV_Error(Error::StsBadArg, "saveMesh: faces: empty (a mesh needs at least one triangle)");
    if (!normals.empty()) {
        detail::readVectors(normals, "normals", L, N);
        checkFinite(N, "normals");
    }
    if (!colors.empty()) {
        detail::readColors(colors, "colors", L, C);
        for (size_t i = 0; i < C.size(); i++)
            for (int k = 0; k < 3; k++)
                if (!(C[i][k] >= 0 && C[i][k] <= 1))
                    CV_Error(Error::StsOutOfRange,
                             format("saveMesh: colors: vertex %zu has %g, outside [0, 1] (RGB "
                                    "floats)", i, C[i][k]));
    }
    int uvDims = 2;
    if (!texCoords.empty()) {
        const Mat m = texCoords.getMat();
        if (m.channels() == 3 || (m.channels() == 1 && m.cols == 3)) {
            uvDims = 3;
            detail::readVectors(texCoords, "texCoords", L, T);
        } else {
            std::vector<Point2d> uv;
            detail::readPoints(texCoords, "texCoords", L, uv);
            T.resize(uv.size());
            for (size_t i = 0; i < uv.size(); i++)
                T[i] = Vec3d(uv[i].x, uv[i].y, 0);
        }
        checkFinite(T, "texCoords", uvDims);
    }

    const std::string ext = lowerExtension(filename);
    if (ext == "off") {
        writeOff(filename, V, F);
        return;
    }
    const char* format_id = exportFormat(ext);
    if (!format_id)
        CV_Error(Error::StsBadArg,
                 format("saveMesh: '%s': unknown extension '%s' (known: obj, ply, stl, gltf, glb, "
                        "off, dae, fbx, x3d, 3mf, x, 3ds)", filename.c_str(), ext.c_str()));

    // One mesh under the root node, one default material; aiScene's destructor frees them all.
    aiScene scene;
    scene.mNumMaterials = 1;
    scene.mMaterials = new aiMaterial*[1];
    scene.mMaterials[0] = new aiMaterial();
    const aiString materialName("default");
    scene.mMaterials[0]->AddProperty(&materialName, AI_MATKEY_NAME);
    scene.mNumMeshes = 1;
    scene.mMeshes = new aiMesh*[1];
    aiMesh* mesh = scene.mMeshes[0] = new aiMesh();
    scene.mRootNode = new aiNode();
    scene.mRootNode->mNumMeshes = 1;
    scene.mRootNode->mMeshes = new unsigned[1]{0};

    mesh->mMaterialIndex = 0;
    mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    mesh->mNumVertices = unsigned(L);
    mesh->mVertices = new aiVector3D[size_t(L)];
    for (int i = 0; i < L; i++)
        mesh->mVertices[i] = aiVector3D(float(V[i][0]), float(V[i][1]), float(V[i][2]));
    if (!N.empty()) {
        mesh->mNormals = new aiVector3D[size_t(L)];
        for (int i = 0; i < L; i++)
            mesh->mNormals[i] = aiVector3D(float(N[i][0]), float(N[i][1]), float(N[i][2]));
    }
    if (!C.empty()) {
        mesh->mColors[0] = new aiColor4D[size_t(L)];
        for (int i = 0; i < L; i++)
            mesh->mColors[0][i] = aiColor4D(float(C[i][0]), float(C[i][1]), float(C[i][2]), 1.f);
    }
    if (!T.empty()) {
        mesh->mTextureCoords[0] = new aiVector3D[size_t(L)];
        mesh->mNumUVComponents[0] = unsigned(uvDims);
        for (int i = 0; i < L; i++)
            mesh->mTextureCoords[0][i] = aiVector3D(float(T[i][0]), float(T[i][1]),
                                                    float(T[i][2]));
    }
    mesh->mNumFaces = unsigned(F.size());
    mesh->mFaces = new aiFace[F.size()];
    for (size_t i = 0; i < F.size(); i++) {
        aiFace& face = mesh->mFaces[i];
        face.mNumIndices = 3;
        face.mIndices = new unsigned[3]{unsigned(F[i][0]), unsigned(F[i][1]), unsigned(F[i][2])};
    }

    Assimp::Exporter exporter;
    if (exporter.Export(&scene, format_id, filename) != AI_SUCCESS)
        CV_Error(Error::StsError, format("saveMesh: cannot write '%s': %s", filename.c_str(),
                                         exporter.GetErrorString()));
}

}  // namespace shading
}  // namespace cv
