"""Triangle scan conversion and shading into NumPy images (OpenCV's cv::shading).

Canvases are H x W x 3 float32 (colours usually in [0, 1]) or uint8 arrays, drawn into in place
(views and slices too); sizes are (width, height) as in cv2.
"""
import os
from typing import Callable, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

SHADE_FLAT: int
SHADE_GOURAUD: int
SHADE_PHONG: int
VISIBILITY_ZBUFFER: int
VISIBILITY_PAINTER: int
CULL_NONE: int
CULL_BACK: int
CULL_FRONT: int

ArrayLike = npt.ArrayLike
Canvas = npt.NDArray[Union[np.float32, np.uint8]]
Vec3 = Union[Sequence[float], npt.NDArray[np.floating]]
ShadeType = Union[int, str]  # SHADE_* or "flat" / "gouraud" / "phong" (any case)


class error(RuntimeError):
    """A cv::Exception raised by the C++ library; str() is its message (what())."""
    code: int
    err: str
    func: str
    file: str
    line: int


class PointLight:
    """A point light: world position, RGB intensity."""
    position: Tuple[float, float, float]
    intensity: Tuple[float, float, float]

    def __init__(self, position: Vec3 = (0, 0, 0), intensity: Vec3 = (1, 1, 1)) -> None: ...


class RenderSettings:
    """How drawMesh3d shades and which faces it keeps.

    Defaults: Gouraud, z-buffer, no culling, zNear 1e-3, no lights (unlit: vertex colours as
    given), ambient (1, 1, 1), ka 0.2, kd 0.7, ks 0.5, shininess 16, textures (for
    drawTexturedMesh3d) sampled with cv2.INTER_LINEAR and cv2.BORDER_REPLICATE, no clear.
    `lights` returns a copy: assign a new list to change it. `clear` starts a new frame: the
    canvas is cleared to `background` (canvas units) and a given depthBuffer to +inf, band by
    band as they are drawn, as setting them first would.
    """
    shadeType: int  # assignable from an int or "flat" / "gouraud" / "phong"
    visibility: int
    cullMode: int
    zNear: float
    lights: list[PointLight]
    ambient: Tuple[float, float, float]
    ka: float
    kd: float
    ks: float
    shininess: float
    textureInterpolation: int
    textureBorder: int
    clear: bool
    background: Tuple[float, float, float]  # assignable from 1 to 4 numbers

    def __init__(self, *, shadeType: ShadeType = ..., visibility: int = ...,
                 cullMode: int = ..., zNear: float = 1e-3, lights: Sequence[PointLight] = (),
                 ambient: Vec3 = (1, 1, 1), ka: float = 0.2, kd: float = 0.7, ks: float = 0.5,
                 shininess: float = 16, textureInterpolation: int = ...,
                 textureBorder: int = ..., clear: bool = False,
                 background: Union[float, Sequence[float]] = (0, 0, 0)) -> None: ...


def flats(canvas: Canvas, vertices: ArrayLike, vcolors: ArrayLike) -> Canvas:
    """Fills one triangle (3 x 2 vertices) with the mean of its 3 vertex colours, in place.
    Returns canvas."""


def gouraud(canvas: Canvas, vertices: ArrayLike, vcolors: ArrayLike) -> Canvas:
    """Fills one triangle (3 x 2 vertices) interpolating its 3 vertex colours, in place.
    Returns canvas."""


def drawMesh(canvas: Canvas, verts2d: ArrayLike, faces: ArrayLike, vcolors: ArrayLike,
             depth: ArrayLike | None = None, shadeType: ShadeType = ...) -> Canvas:
    """Draws a mesh (L x 2 vertices, K x 3 faces, L x 3 colours, L depths or None) onto canvas
    in place, in painter's order (largest mean depth first). Returns canvas."""


def render(verts2d: ArrayLike, faces: ArrayLike, vcolors: ArrayLike, depth: ArrayLike | None,
           shadeType: ShadeType = ..., size: Tuple[int, int] = (512, 512),
           background: float | Sequence[float] = (1, 1, 1)) -> npt.NDArray[np.float32]:
    """Renders a mesh into a new height x width x 3 float32 image filled with background;
    size is (width, height)."""


def computeNormals(verts3d: ArrayLike, faces: ArrayLike
                   ) -> Tuple[npt.NDArray[np.float32], npt.NDArray[np.float32]]:
    """Returns (vertexNormals L x 3, faceNormals K x 3), float32 unit vectors (zero if
    degenerate)."""


def lookAt(eye: Vec3, target: Vec3, up: Vec3
           ) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Returns (rvec, tvec), 3 x 1 float64 each: the OpenCV pose of a camera at eye looking at
    target, up appearing up."""


def drawMesh3d(canvas: Canvas, verts3d: ArrayLike, faces: ArrayLike, vcolors: ArrayLike,
               cameraMatrix: ArrayLike, rvec: ArrayLike, tvec: ArrayLike,
               settings: RenderSettings = ..., normals: ArrayLike | None = None,
               depthBuffer: npt.NDArray[np.float32] | None = None
               ) -> Tuple[Canvas, npt.NDArray[np.float32], npt.NDArray[np.int32]]:
    """Draws a 3D mesh seen by an OpenCV camera into canvas in place. depthBuffer (H x W float32)
    is tested against and updated in place, or created (+inf) when None. Returns (canvas,
    depthBuffer, faceIds), faceIds H x W int32 (-1 where no face)."""


def drawTexturedMesh3d(canvas: Canvas, verts3d: ArrayLike, faces: ArrayLike,
                       texCoords: ArrayLike, texture: npt.NDArray[Union[np.float32, np.uint8]],
                       cameraMatrix: ArrayLike, rvec: ArrayLike, tvec: ArrayLike,
                       settings: RenderSettings = ..., normals: ArrayLike | None = None,
                       depthBuffer: npt.NDArray[np.float32] | None = None
                       ) -> Tuple[Canvas, npt.NDArray[np.float32], npt.NDArray[np.int32]]:
    """drawMesh3d with a texture (H x W x 3) in place of the vertex colours: texCoords L x 2 in
    texture pixels, interpolated perspective-correctly and sampled as cv2.remap samples
    (settings.textureInterpolation, settings.textureBorder); lit, the texel takes the vertex
    colour's place. Returns (canvas, depthBuffer, faceIds) as drawMesh3d."""


def loadMesh(filename: str | os.PathLike[str]
             ) -> Tuple[npt.NDArray[np.float32], npt.NDArray[np.int32],
                        npt.NDArray[np.float32] | None, npt.NDArray[np.float32] | None,
                        npt.NDArray[np.float32] | None]:
    """Loads a triangle mesh (assimp formats). Returns (vertices L x 3, faces K x 3, normals,
    colors, texCoords); the last three None where the file has none."""


def saveMesh(filename: str | os.PathLike[str], vertices: ArrayLike, faces: ArrayLike,
             normals: ArrayLike | None = None, colors: ArrayLike | None = None,
             texCoords: ArrayLike | None = None) -> None:
    """Saves a triangle mesh in the format its extension names (.obj, .ply, .stl, .gltf, .glb,
    .off, ...)."""


# ---- polygons (bind_polygon.cpp) ------------------------------------------------------------

FILL_EVEN_ODD: int
FILL_NONZERO: int

Contours = Union[Sequence[ArrayLike], npt.NDArray[np.generic]]


def fillPolygons(canvas: Canvas, polygons: Contours, color: float | Sequence[float],
                 fillRule: int = ...) -> Canvas:
    """Fills polygons (a list of N x 2 contours as cv2.fillPoly takes them, one N x 2 array or a
    K x N x 2 array; holes and self-intersections allowed) in place, where the winding number
    around (x + e, y + e^2) is odd (FILL_EVEN_ODD, the default) or nonzero (FILL_NONZERO).
    Returns canvas."""


def triangulatePolygons(polygons: Contours, fillRule: int = ..., returnVertices: bool = ...
                        ) -> Union[npt.NDArray[np.int32],
                                   Tuple[npt.NDArray[np.int32], npt.NDArray[np.float64]]]:
    """Triangles covering what fillPolygons covers, each sample at most once: faces, K x 3 int32
    indices into the contours' points concatenated in order, then the points added where
    contours cross; with returnVertices=True, (faces, vertices), vertices N x 2 float64 pixels
    (the snapped points, then grid points (1/256 px) near the crossings). Exact: crossings off
    the grid move to grid points checked to change no sample; edges thousands of pixels long,
    and rarely dense crossings no grid point suits, fall back to snap rounding (samples within
    1/512 px of an edge may differ)."""


LINE_BRESENHAM: int
LINE_DDA: int


def lines(canvas: Canvas, points: ArrayLike, colors: ArrayLike,
          algorithm: int = ...) -> Canvas:
    """Draws segments (points[2i], points[2i + 1]) in place, colours (2N x 3, one per point)
    interpolated along each. LINE_BRESENHAM (default): endpoints rounded, the pixels of
    cv2.line(..., 1, cv2.LINE_8); LINE_DDA: 1/256 px endpoints, exact fixed-point DDA.
    Returns canvas."""


def texturedTriangles(canvas: Canvas, verts2d: ArrayLike, faces: ArrayLike,
                      texCoords: ArrayLike, texture: npt.NDArray[Union[np.float32, np.uint8]],
                      interpolation: int = ..., borderMode: int = ...) -> Canvas:
    """Draws triangles textured from an H x W x 3 image, in place, in face order. texCoords:
    L x 2 texture pixel coordinates (as cv2.remap's maps); interpolation cv2.INTER_NEAREST or
    cv2.INTER_LINEAR (default); borderMode cv2.BORDER_* (default BORDER_REPLICATE). Each
    covered pixel equals cv2.remap with float32 maps of the interpolated coordinates.
    Returns canvas."""


def forEachSample(canvasSize: Tuple[int, int], vertices: ArrayLike,
                  fn: Callable[[int, int, Tuple[float, float, float]], None],
                  depths: ArrayLike | None = None) -> None:
    """Calls fn(x, y, w) per covered sample (exactly those flats covers) with its barycentric
    weights w for the vertices in the order given. With depths (the vertices' camera Zc > 0)
    the weights are perspective-correct."""


def forEachSpan(canvasSize: Tuple[int, int], vertices: ArrayLike,
                fn: Callable[[int, int, int, Tuple[float, float, float],
                              Tuple[float, float, float]], None],
                depths: ArrayLike | None = None) -> None:
    """Calls fn(y, xBegin, xEnd, w, dwdx) per span of covered samples (exactly those flats
    covers): row y, columns [xBegin, xEnd), barycentric weights w at xBegin for the vertices in
    the order given, and their change per pixel dwdx. With depths (camera Zc > 0), w and dwdx
    are h_i = w_i / z_i: h / sum(h) are the perspective-correct weights, 1 / sum(h) the
    depth."""
