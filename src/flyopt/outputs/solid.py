# mypy: disable-error-code="import-untyped,import-not-found"
# (OCP ships no type information: its imports are untyped here, and only here)
"""The designed wheel as a solid, and its STEP file (the ``cad`` extra: OpenCASCADE through OCP).

:func:`solid_of` builds the wheel as designed, in millimetres, its axis on z
and its mid-plane at z = 0: the axial section of
:func:`flyopt.outputs.drawing.section_blocks` (rim, web, hub or disc, and the
bore) as coaxial annuli fused together; a ``rim_arms`` wheel's arms, each an
elliptical cylinder (major axis along the circumference, minor along the
axis) bounded by the hub's and the rim's cylinders, at the angles the front
view draws them; and the hub's DIN 6885-1 keyway (:func:`flyopt.outputs.drawing.keyway`),
a slot of width b from the bore to the depth d + t2 over it at +y, cut
through the keyed part's whole length. Edges are sharp: no fillets, no draft,
no machining allowance (the drawing's notes give those).

:func:`write_step` writes the solid as STEP (AP214, millimetres) atomically,
reads the written file back and checks that its volume and its moment of
inertia about the axis are the built solid's to 1e-6: a STEP that does not
read back as the wheel is never left under its name (a
:class:`flyopt.errors.BrokenInvariant`).

OCP (``cadquery-ocp-novtk``) is imported only here and only when a solid is
asked for; without it :func:`require_ocp` refuses in one line naming the extra.
"""

from __future__ import annotations

import contextlib
import errno
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from flyopt.outputs.drawing import CAD_EXTRA, keyway, section_blocks

if TYPE_CHECKING:
    import os

    from flyopt.design.result import Design

__all__ = [
    "READ_BACK_TOLERANCE",
    "Solid",
    "require_ocp",
    "solid_of",
    "solid_properties",
    "read_step",
    "write_step",
]

#: Relative difference allowed between the solid written and the STEP read back (volume and J).
READ_BACK_TOLERANCE = 1e-6
#: Relative accuracy asked of OpenCASCADE's adaptive volume integration.
_GPROP_EPS = 1e-10
_MM = 1e3  # mm per m


@dataclass(frozen=True)
class Solid:
    """A wheel's solid as its STEP file reads back: volume and the axial moment, in SI.

    Attributes
    ----------
    volume : float
        [m^3].
    moment : float
        Integral of r^2 dV about the wheel's axis [m^5] (J per unit density).
    density : float
        [kg/m^3], the design's material.
    """

    volume: float
    moment: float
    density: float

    @property
    def mass(self) -> float:
        """[kg]."""
        return self.density * self.volume

    @property
    def inertia(self) -> float:
        """About the axis [kg*m^2]."""
        return self.density * self.moment


def require_ocp() -> Any:
    """The OCP package, or a one-line refusal naming the extra that brings it."""
    try:
        import OCP
    except ImportError:
        raise ImportError(f"a STEP solid needs OpenCASCADE (cadquery-ocp-novtk): pip install '{CAD_EXTRA}'") from None
    return OCP


def solid_of(design: Design) -> Any:
    """The wheel of ``design`` as one OpenCASCADE solid (a TopoDS_Shape) [mm], its axis on z.

    Raises
    ------
    ValueError
        ``design`` is not a design (no dimensions).
    """
    require_ocp()
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Common, BRepAlgoAPI_Cut
    from OCP.BRepBuilderAPI import (
        BRepBuilderAPI_MakeEdge,
        BRepBuilderAPI_MakeFace,
        BRepBuilderAPI_MakeWire,
        BRepBuilderAPI_Transform,
    )
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakePrism
    from OCP.gp import gp_Ax1, gp_Ax2, gp_Dir, gp_Elips, gp_Pnt, gp_Trsf, gp_Vec

    blocks, arms = section_blocks(design)
    blocks_mm = [(name, r0 * _MM, r1 * _MM, w * _MM) for name, r0, r1, w in blocks]
    shape = None
    for _name, r0, r1, w in blocks_mm:
        shape = _fuse(shape, _annulus(r0, r1, w))
    if arms is not None:
        r_hub, r_rim, major, minor = (v * _MM for v in arms)
        tall = 2.0 * max(w for *_rest, w in blocks_mm) + minor
        tube = _annulus(r_hub, r_rim, tall)
        ellipse = gp_Elips(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 1, 0), gp_Dir(1, 0, 0)), major / 2.0, minor / 2.0)
        face = BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(ellipse).Edge()).Wire()).Face()
        bar = BRepPrimAPI_MakePrism(face, gp_Vec(0, 2.0 * r_rim, 0)).Shape()  # along +y, from the axis out
        arm = _done(BRepAlgoAPI_Common(bar, tube), "an arm between the hub and the rim")
        n_arms = design.n_arms or 0
        for index in range(n_arms):
            turn = gp_Trsf()
            # the front view's angles (pi/2 + 2 pi (k + 1/2) / n): clear of the keyway at +y
            turn.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 2.0 * math.pi * (index + 0.5) / n_arms)
            shape = _fuse(shape, BRepBuilderAPI_Transform(arm, turn, True).Shape())
    b_key, t2 = (v * _MM for v in keyway(design))
    if b_key > 0.0:
        r_bore = (design.bore or 0.0) * _MM / 2.0
        keyed = next(w for _name, r0, _r1, w in blocks_mm if math.isclose(r0, r_bore))
        slot = BRepPrimAPI_MakeBox(gp_Pnt(-b_key / 2.0, 0.0, -keyed / 2.0), b_key, r_bore + t2, keyed).Shape()
        shape = _done(BRepAlgoAPI_Cut(shape, slot), "the keyway")
    return _one_solid(shape)


def _annulus(r_inner, r_outer, width):
    """A centred annulus [mm]: a cylinder, less its bore when r_inner > 0."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt

    def cylinder(radius):
        return BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -width / 2.0), gp_Dir(0, 0, 1)), radius, width).Shape()

    outer = cylinder(r_outer)
    return outer if r_inner <= 0.0 else _done(BRepAlgoAPI_Cut(outer, cylinder(r_inner)), "an annulus")


def _fuse(shape, other):
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Fuse

    return other if shape is None else _done(BRepAlgoAPI_Fuse(shape, other), "the parts fused")


def _done(operation, what):
    """The result of an OpenCASCADE operation, or BrokenInvariant saying which one failed."""
    from flyopt.errors import BrokenInvariant

    operation.Build()
    if not operation.IsDone():
        raise BrokenInvariant(f"the wheel's solid could not be built: {what} failed in OpenCASCADE")
    return operation.Shape()


def _one_solid(shape):
    """``shape`` itself if it is a valid shape of exactly one solid; BrokenInvariant otherwise."""
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer

    from flyopt.errors import BrokenInvariant

    explorer, count = TopExp_Explorer(shape, TopAbs_SOLID), 0
    while explorer.More():
        count += 1
        explorer.Next()
    if count != 1 or not BRepCheck_Analyzer(shape).IsValid():
        raise BrokenInvariant(f"the wheel's solid is not one valid solid ({count} solids)")
    return shape


def solid_properties(shape: Any) -> tuple[float, float]:
    """(volume [m^3], integral of r^2 dV about the z axis [m^5]) of a solid built in mm."""
    require_ocp()
    from OCP.BRepGProp import BRepGProp
    from OCP.gp import gp_Ax1, gp_Dir, gp_Pnt
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props, _GPROP_EPS, True)
    axis = gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1))
    return props.Mass() * 1e-9, props.MomentOfInertia(axis) * 1e-15


@contextlib.contextmanager
def _quiet():
    """OpenCASCADE's messages below a failure kept off stdout (its STEP statistics), for the block only."""
    from OCP.Message import Message, Message_Gravity

    printers = list(Message.DefaultMessenger_s().Printers())
    levels = [printer.GetTraceLevel() for printer in printers]
    for printer in printers:
        printer.SetTraceLevel(Message_Gravity.Message_Fail)
    try:
        yield
    finally:
        for printer, level in zip(printers, levels):
            printer.SetTraceLevel(level)


def read_step(path: str | os.PathLike[str]) -> Any:
    """The shape of a STEP file, in mm (OpenCASCADE converts the file's unit); OSError if it does not read."""
    require_ocp()
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_Reader

    with _quiet():
        reader = STEPControl_Reader()
        if reader.ReadFile(str(path)) != IFSelect_RetDone or reader.TransferRoots() < 1:
            raise OSError(f"{str(path)!r} does not read as STEP")
        return reader.OneShape()


def write_step(design: Design, path: str | os.PathLike[str], density: float, name: str = "flywheel") -> Solid:
    """Write the solid of ``design`` to ``path`` as STEP (AP214, mm), atomically, and read it back.

    Parameters
    ----------
    design : flyopt.design.result.Design
    path : path
        The file; its folder must exist.
    density : float
        The material's [kg/m^3], for the mass and J of what is returned.
    name : str
        The product's name in the file.

    Returns
    -------
    Solid
        The volume and axial moment of the file as read back.

    Raises
    ------
    BrokenInvariant
        The written file does not read back as the solid built (volume or J
        off by more than :data:`READ_BACK_TOLERANCE`); nothing is written.
    OutputError
        The file cannot be written.
    """
    require_ocp()
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.Interface import Interface_Static
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer

    from flyopt.errors import BrokenInvariant, OutputError
    from flyopt.outputs.files import Temporary

    shape = solid_of(design)
    built = solid_properties(shape)
    temporary = Temporary(path)
    try:
        temporary.close()  # OpenCASCADE writes the file by its name
        with _quiet():
            writer = STEPControl_Writer()
            Interface_Static.SetCVal_s("write.step.schema", "AP214IS")
            Interface_Static.SetCVal_s("write.step.unit", "MM")
            Interface_Static.SetCVal_s("write.step.product.name", name)
            if writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone:
                raise BrokenInvariant("the wheel's solid could not be transferred to STEP")
            if writer.Write(str(temporary.path)) != IFSelect_RetDone:
                raise OutputError(errno.EIO, "cannot be written: OpenCASCADE's STEP writer failed", str(path))
            read = solid_properties(read_step(temporary.path))
        for what, was, now in zip(("volume", "J"), built, read):
            if not math.isclose(now, was, rel_tol=READ_BACK_TOLERANCE):
                raise BrokenInvariant(f"the STEP file reads back with {what} {now:.9g}, not the solid's {was:.9g}")
    except BaseException:
        temporary.discard()
        raise
    temporary.finish()
    return Solid(read[0], read[1], density)
