# mypy: disable-error-code="valid-type, misc"
"""A Warp kernel that casts a ray sensor's rays with one thread a ray
against the few geoms the sensor can see (``FieldRays``): MuJoCo Warp's
own per-geom test (``_ray_geom_mesh``, which reads the field each world's
geom points at), so the hits are its direct test's, bit for bit. Imported
only where Warp and MuJoCo Warp are (mjlab's envs), once ``ray_sensors.terrain_rays``
has checked the private names it imports (``rse._adapters.private``)."""

from __future__ import annotations

# Warp's array annotations are calls, which mypy cannot read: the first
# line of this file.
import warp as wp
from mujoco_warp._src.ray import _ray_geom_mesh
from mujoco_warp._src.types import MJ_MAXVAL, vec6

MODEL_FIELDS = (
    "nmeshface",
    "body_weldid",
    "geom_type",
    "geom_bodyid",
    "geom_dataid",
    "geom_matid",
    "geom_group",
    "geom_size",
    "geom_rgba",
    "mesh_vertadr",
    "mesh_faceadr",
    "mesh_vert",
    "mesh_face",
    "hfield_size",
    "hfield_nrow",
    "hfield_ncol",
    "hfield_adr",
    "hfield_data",
    "mat_rgba",
)
"""The fields of MuJoCo Warp's model that its ray test reads, in its
argument order: ``GeomModel``'s, copied from the model at each cast."""


@wp.struct
class GeomModel:
    """What ``_ray_geom_mesh`` reads of the model, in one kernel argument."""

    nmeshface: int
    body_weldid: wp.array(dtype=int)
    geom_type: wp.array(dtype=int)
    geom_bodyid: wp.array(dtype=int)
    geom_dataid: wp.array2d(dtype=int)
    geom_matid: wp.array2d(dtype=int)
    geom_group: wp.array(dtype=int)
    geom_size: wp.array2d(dtype=wp.vec3)
    geom_rgba: wp.array2d(dtype=wp.vec4)
    mesh_vertadr: wp.array(dtype=int)
    mesh_faceadr: wp.array(dtype=int)
    mesh_vert: wp.array(dtype=wp.vec3)
    mesh_face: wp.array(dtype=wp.vec3i)
    hfield_size: wp.array(dtype=wp.vec4)
    hfield_nrow: wp.array(dtype=int)
    hfield_ncol: wp.array(dtype=int)
    hfield_adr: wp.array(dtype=int)
    hfield_data: wp.array(dtype=float)
    mat_rgba: wp.array2d(dtype=wp.vec4)


@wp.func
def _ray_geom(
    m: GeomModel,
    geom_xpos_in: wp.array2d(dtype=wp.vec3),
    geom_xmat_in: wp.array2d(dtype=wp.mat33),
    worldid: int,
    pnt: wp.vec3,
    vec: wp.vec3,
    geomgroup: vec6,
    flg_static: bool,
    bodyexclude: int,
    geomid: int,
):
    # MuJoCo Warp's ray test of one geom, as its direct ray cast calls it.
    return _ray_geom_mesh(
        m.nmeshface,
        m.body_weldid,
        m.geom_type,
        m.geom_bodyid,
        m.geom_dataid,
        m.geom_matid,
        m.geom_group,
        m.geom_size,
        m.geom_rgba,
        m.mesh_vertadr,
        m.mesh_faceadr,
        m.mesh_vert,
        m.mesh_face,
        m.hfield_size,
        m.hfield_nrow,
        m.hfield_ncol,
        m.hfield_adr,
        m.hfield_data,
        m.mat_rgba,
        geom_xpos_in,
        geom_xmat_in,
        worldid,
        pnt,
        vec,
        geomgroup,
        flg_static,
        bodyexclude,
        geomid,
    )


@wp.kernel(enable_backward=False)
def cast_on_candidates(
    m: GeomModel,
    # Data in:
    geom_xpos_in: wp.array2d(dtype=wp.vec3),
    geom_xmat_in: wp.array2d(dtype=wp.mat33),
    # In:
    candidates: wp.array(dtype=int),
    pnt: wp.array2d(dtype=wp.vec3),
    vec: wp.array2d(dtype=wp.vec3),
    geomgroup: vec6,
    flg_static: bool,
    bodyexclude: wp.array(dtype=int),
    # Out:
    dist_out: wp.array2d(dtype=float),
    geomid_out: wp.array2d(dtype=int),
    normal_out: wp.array2d(dtype=wp.vec3),
):
    worldid, rayid = wp.tid()
    min_dist = float(MJ_MAXVAL)
    min_geomid = int(-1)
    min_normal = wp.vec3()
    # Ascending geom ids and a strict minimum: at a tie the lowest id
    # wins, as in MuJoCo Warp's tiled reduction over all geoms.
    for i in range(candidates.shape[0]):
        geomid = candidates[i]
        origin = pnt[worldid, rayid]
        dist, normal = _ray_geom(m, geom_xpos_in, geom_xmat_in, worldid, origin, vec[worldid, rayid], geomgroup, flg_static, bodyexclude[rayid], geomid)
        if dist < 0.0:
            dist = float(MJ_MAXVAL)
        if dist < min_dist:
            min_dist = dist
            min_geomid = geomid
            min_normal = normal
    if min_dist >= MJ_MAXVAL:
        dist_out[worldid, rayid] = -1.0
    else:
        dist_out[worldid, rayid] = min_dist
    geomid_out[worldid, rayid] = min_geomid
    normal_out[worldid, rayid] = min_normal


def geom_model(model: object) -> GeomModel:
    """``GeomModel`` of MuJoCo Warp's model struct (its arrays, not copies)."""
    out = GeomModel()
    for name in MODEL_FIELDS:
        setattr(out, name, getattr(model, name))
    return out
