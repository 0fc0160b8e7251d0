"""Scene randomisation (the paper's Table I) and the Mitsuba scene dictionary.

Units: metres, radians in code (degrees only in config keys named ``_deg``). World frame: z up, the ground
plane is z = 0. ``sample_scene`` draws every random parameter from a numpy Generator into a JSON-serialisable
dict (stored with each sample); ``build_scene`` turns those parameters plus posed meshes into a scene dict
for ``mi.load_dict``: nothing random happens after sampling.

Ground-truth normals are given in camera coordinates with the project's convention: x toward image right,
y toward image up, z toward the camera (a surface facing the camera has normal (0, 0, 1)). Mitsuba's own camera
frame has x toward image LEFT and z away from the camera (docs/platform-facts.md); ``camera_axes`` converts.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import asdict, dataclass, fields, replace
from typing import Any

import numpy as np

from .errors import SimError
from .meshes import ObjectModel, Part, stable_poses

IMX250MZR_WIDTH_MM = 2448 * 3.45e-3
"""Active width of the IMX250MZR (2448 pixels of 3.45 um)."""

COLOUR_PARAM = {"pplastic": "diffuse_reflectance", "roughplastic": "diffuse_reflectance",
                "plastic": "diffuse_reflectance", "diffuse": "reflectance"}
"""BSDF types whose colour is randomised (Table I "material colour"), and the parameter that holds it."""
ALPHA_TYPES = ("pplastic", "roughplastic", "roughconductor", "roughdielectric")
"""BSDF types whose roughness alpha is randomised (Table I): Mitsuba's microfacet BSDFs, whose lobe
(``distribution``) is "beckmann" (the default) or "ggx" (``ggx_lobes``)."""
FINISHES = ("rough", "smooth", "either")
BACKGROUNDS = ("plain", "checkerboard", "noise")
BACKGROUND_MATERIALS = ("diffuse", "pplastic")
ANGLES_ANY_SIGN = ("yaw_deg", "camera_azimuth_deg", "light_azimuth_deg", "ring_azimuth_deg", "camera_roll_deg")
FULL_RING = (0.0, 360.0)
"""``SceneConfig.ring_azimuth_deg`` of a whole ring."""


@dataclass(frozen=True)
class SceneConfig:
    """Randomisation ranges; a pair ``(lo, hi)`` is a uniform draw. Defaults follow the paper's Table I where it
    gives one (camera and light shells, light intensity, colour, roughness); the rest are this project's."""

    camera_radius_m: tuple[float, float] = (0.4, 0.49)
    camera_polar_deg: tuple[float, float] = (0.0, 60.0)
    """Angle of the camera from the vertical above the object."""
    camera_azimuth_deg: tuple[float, float] = (0.0, 360.0)
    """Direction of the camera from the object, counter-clockwise from world +x (270 = from -y: image up is +y)."""
    camera_target_jitter_m: float = 0.003
    camera_roll_deg: float = 0.0
    """The line camera turned about its optical axis, degrees (a camera mounted out of square; the second camera of
    ``ViewConfig`` is not turned): positive turns the camera clockwise as seen from behind it, so the scene turns
    counter-clockwise in the image (image up at the top). Fixed, not drawn: a mount is turned once, not per part;
    0 = world z up in the image, as every set before it."""
    focal_length_mm: float = 50.0
    sensor_width_mm: float = IMX250MZR_WIDTH_MM
    object_xy_m: float = 0.02
    """The object rests at a uniform (x, y) in [-object_xy_m, object_xy_m]^2."""
    yaw_deg: tuple[float, float] = (0.0, 360.0)
    """Rotation of the resting object about the vertical (a fixture on a line narrows it)."""
    rest_pose: int = -1
    """Index into the mesh's stable resting poses (most probable first); -1 = drawn by their probabilities."""
    light_radius_m: tuple[float, float] = (1.0, 1.5)
    light_polar_deg: tuple[float, float] = (0.0, 60.0)
    light_azimuth_deg: tuple[float, float] = (0.0, 360.0)
    light_intensity: tuple[float, float] = (2.25, 3.375)
    """Spot light radiant intensity (W/sr, Mitsuba units)."""
    light_cutoff_deg: float = 15.0
    ambient_radiance: float = 0.02
    """Constant environment (keeps shadows from being exactly black); 0 = none."""
    ambient_gradient: float = 0.0
    """A dome brighter on one side: the environment's radiance is ``ambient_radiance * (1 + g * w_x)`` for a
    direction w (unit vector, world +x is along the fixture, image right on the line presets), g in [0, 1]; 0 =
    uniform. Under a uniform dome a matte face looks the same whatever its tilt; under this one its irradiance is
    ``pi L (1 + 2/3 g n_x)``, so a tilt of the surface along x changes intensity to first order (at g = 0.8 a 3 deg
    dent flank by 2.8 %, a 10 deg one by 9 %): a segmented dome with one side's LEDs dimmed does it in one shot. The
    mean over the hemisphere stays ``ambient_radiance``."""
    ambient_gradient_azimuth_deg: float = 0.0
    """Where the gradient dome's bright side lies: degrees from world +x toward +y (0: +x, as above; 180: -x), so
    ``w_x`` above becomes the direction's component along that azimuth. Two frames of one part under azimuths 0 and
    180 are the two halves of a segmented dome lit in turn (photometric stereo): their sum is the uniform dome's
    frame, their normalised difference the surface's tilt along x."""
    ring_radiance: float = 0.0
    """A low-angle ring light (dark field) added to the environment: radiance ``ring_radiance`` from every azimuth
    at elevations ``ring_elevation_deg`` above the ground; 0 = none. A smooth face mirrors it away from a camera
    that looks down more steeply, so it is dark there; a rough patch (a scratch, a stain) spreads it into the camera.
    On a horizontal face its irradiance is ``pi L (cos^2 e_lo - cos^2 e_hi)`` (e: elevation); on a face tilted
    toward the ring it is larger. With ``ambient_gradient`` the dome under the ring is the gradient dome (one
    environment map holds both, ``ring_dict``)."""
    ring_elevation_deg: tuple[float, float] = (5.0, 15.0)
    ring_azimuth_deg: tuple[float, float] = FULL_RING
    """The azimuths the ring covers, degrees from world +x toward +y (lo < hi, at most 360 apart): a whole ring by
    default, a sector otherwise. A sector high enough to be mirrored into the camera by a face (opposite the camera,
    at the camera's elevation) is a bright-field panel: the smooth face shows it, a rough patch spreads its mirrored
    light away and goes dark. Its irradiance on a horizontal face is the whole ring's times the sector's share."""
    ring_fringe_period_deg: float = 0.0
    """Fringes across the ring light (deflectometry): its radiance times ``1 + ring_fringe_depth * cos(2 pi (e -
    e_lo) / period)`` at elevation e (e_lo: the ring's lower edge), so a bright-field panel carries stripes of
    this period; 0 = uniform. A smooth face mirrors one stripe; a dent's slope s moves the mirror image by 2 s
    across the stripes and changes the face's brightness there, where a uniform panel hides a shallow dent whose
    mirror image stays on the panel. A whole number of periods across the ring keeps its mean radiance."""
    ring_fringe_depth: float = 0.5
    """The fringes' modulation depth, 0-1 (0.5: the dark stripe at half the mean, so a rough patch that averages
    the panel still differs from the face at every stripe)."""
    ring_fringe_phase_deg: float = 0.0
    """The fringes' phase, degrees, added inside the cosine: ``cos(2 pi (e - e_lo) / period + phase)``. Frames of
    the same part at phases 0 and 90 beside one under the uniform panel give each pixel the phase of the stripe its
    face mirrors (phase-shifting deflectometry: the phase moves by 360 * 2 s / period for a slope s)."""
    front_light_radiance: float = 0.0
    """A flat light strip lying on the belt in front of the part, on the camera's side (in the fixture's base):
    Lambertian, radiance ``front_light_radiance`` upward, 0 = none. A vertical face turned toward a camera that
    looks down at elevation e mirrors the belt in front of it (a point h above the belt sees the belt
    h / tan e further out), which no light above the belt can fill: the strip puts such front faces in bright
    field, as the panel (``ring_azimuth_deg``) does the top face. The camera sees the strip directly, beside
    the part (it clips there, off the part)."""
    front_light_span_m: tuple[float, float] = (0.011, 0.040)
    """Near and far edge of the strip, metres from the fixture's centre (world origin) toward
    ``front_light_azimuth_deg``."""
    front_light_width_m: float = 0.05
    """The strip's length across that direction, metres, centred."""
    front_light_azimuth_deg: float = 270.0
    """Where the strip lies, degrees from world +x toward +y (270: -y, the line presets' camera side)."""
    colour: tuple[float, float] = (0.0, 1.0)
    background_colour: tuple[float, float] | None = None
    """Reflectance range of the ground's colours; None = ``colour``'s."""
    alpha_rough: tuple[float, float] = (0.1, 0.7)
    alpha_smooth: tuple[float, float] = (0.001, 0.011)
    ggx_share: float = 0.0
    """The share of parts whose microfacet materials (``ALPHA_TYPES``) have a GGX lobe instead of Mitsuba's default
    Beckmann one, in [0, 1]. Drawn per part on its own stream (``sim.dataset.draw_sample``), so every other draw
    stays; a material whose spec names its ``distribution`` keeps it. A moulded part's lobe is neither, and another
    renderer may use either: GGX's longer tail spreads a mirrored light into a wider halo at the same alpha."""
    background_size_m: float = 1.0
    backgrounds: tuple[str, ...] = BACKGROUNDS
    max_depth: int = 6

    def __post_init__(self) -> None:
        for f in fields(self):
            v = getattr(self, f.name)
            if f.name == "rest_pose":
                if not isinstance(v, int) or v < -1:
                    raise SimError(f"scene.rest_pose: an index >= 0 of a stable pose, or -1 for random; got {v!r}")
                continue
            if v is None:
                continue
            if f.name == "backgrounds":
                bad = [b for b in v if b not in BACKGROUNDS]
                if bad or not v:
                    raise SimError(f"scene.backgrounds: unknown {bad or v}; choose from {', '.join(BACKGROUNDS)}")
                continue
            numbers = v if isinstance(v, tuple) else (v,)
            if not all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in numbers):
                raise SimError(f"scene.{f.name}: expected numbers, got {v!r}")
            if isinstance(v, tuple):
                if len(v) != 2 or not all(np.isfinite(x) for x in v) or v[0] > v[1]:
                    raise SimError(f"scene.{f.name}: need a range (lo, hi) with lo <= hi, got {v}")
                if min(v) < 0 and f.name not in ANGLES_ANY_SIGN:
                    raise SimError(f"scene.{f.name}: values must be >= 0, got {v}")
            elif not (np.isfinite(v) and (v >= 0 or f.name in ANGLES_ANY_SIGN)):
                raise SimError(f"scene.{f.name}: must be a number >= 0, got {v}")
        for key in ("camera_polar_deg", "light_polar_deg"):
            if getattr(self, key)[1] >= 90:
                raise SimError(f"scene.{key}: must stay above the ground (< 90 degrees), got {getattr(self, key)}")
        for key in ("alpha_rough", "alpha_smooth"):
            if getattr(self, key)[0] <= 0:
                raise SimError(f"scene.{key}: roughness alpha must be > 0, got {getattr(self, key)}")
        for key in ("colour", "background_colour"):
            if getattr(self, key) is not None and getattr(self, key)[1] > 1:
                raise SimError(f"scene.{key}: reflectance must be in [0, 1], got {getattr(self, key)}")
        if self.camera_radius_m[0] <= 0 or self.focal_length_mm <= 0 or self.sensor_width_mm <= 0:
            raise SimError("scene: camera_radius_m, focal_length_mm and sensor_width_mm must be > 0")
        if self.camera_radius_m[0] * np.cos(np.radians(self.camera_polar_deg[1])) < 0.05:
            raise SimError(f"scene: the camera can come within 5 cm of the ground ({self.camera_radius_m} m at "
                           f"{self.camera_polar_deg[1]} degrees)")
        if self.ggx_share > 1:
            raise SimError(f"scene.ggx_share: a share of parts, in [0, 1], got {self.ggx_share}")
        if self.ambient_gradient > 1:
            raise SimError(f"scene.ambient_gradient must be in [0, 1], got {self.ambient_gradient}")
        if self.ambient_gradient_azimuth_deg >= 360:
            raise SimError(f"scene.ambient_gradient_azimuth_deg must be in [0, 360), got "
                           f"{self.ambient_gradient_azimuth_deg}")
        if self.ring_elevation_deg[1] >= 90 or self.ring_elevation_deg[0] >= self.ring_elevation_deg[1]:
            raise SimError(f"scene.ring_elevation_deg: need elevations lo < hi < 90 degrees, got "
                           f"{self.ring_elevation_deg}")
        lo, hi = self.ring_azimuth_deg
        if not (-360 <= lo < hi <= lo + 360 <= 720):
            raise SimError(f"scene.ring_azimuth_deg: need azimuths -360 <= lo < hi <= lo + 360 <= 720 degrees, got "
                           f"{self.ring_azimuth_deg}")
        if self.ring_fringe_period_deg and not self.ring_radiance:
            raise SimError("scene.ring_fringe_period_deg: fringes need a ring light (scene.ring_radiance > 0)")
        if self.ring_fringe_depth > 1:
            raise SimError(f"scene.ring_fringe_depth must be in [0, 1], got {self.ring_fringe_depth}")
        if self.front_light_radiance and (self.front_light_span_m[0] >= self.front_light_span_m[1]
                                          or self.front_light_width_m <= 0):
            raise SimError(f"scene.front_light_span_m: need near < far (metres) and a width > 0, got "
                           f"{self.front_light_span_m} and {self.front_light_width_m}")
        if self.front_light_azimuth_deg >= 360:
            raise SimError(f"scene.front_light_azimuth_deg must be in [0, 360), got {self.front_light_azimuth_deg}")
        if self.max_depth < 2:
            raise SimError(f"scene.max_depth must be >= 2, got {self.max_depth}")

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> SceneConfig:
        known = {f.name for f in fields(cls)}
        bad = sorted(set(d) - known)
        if bad:
            raise SimError(f"scene: unknown keys {bad}; known: {', '.join(sorted(known))}")
        return cls(**{k: tuple(v) if isinstance(v, list) else v for k, v in d.items()})

    def to_dict(self) -> dict[str, Any]:
        """The config as a dict; keys added after sets were rendered are left out at their defaults, so the
        manifests of those sets still match on resume."""
        d = asdict(self)
        for key in LATER_KEYS:
            if d[key] == getattr(SceneConfig, key):
                d.pop(key)
        return d


LATER_KEYS = ("camera_azimuth_deg", "light_azimuth_deg", "yaw_deg", "rest_pose", "background_colour",
              "ambient_gradient", "ambient_gradient_azimuth_deg", "ring_radiance", "ring_elevation_deg",
              "ring_azimuth_deg", "ring_fringe_period_deg", "ring_fringe_depth", "ring_fringe_phase_deg",
              "front_light_radiance",
              "front_light_span_m", "front_light_width_m", "front_light_azimuth_deg", "ggx_share", "camera_roll_deg")
"""SceneConfig keys added after renderer version 2's first sets (their defaults draw what the sets drew)."""


def _uniform(rng: np.random.Generator, r: tuple[float, float]) -> float:
    return float(rng.uniform(r[0], r[1]))


def _on_shell(rng: np.random.Generator, radius: tuple[float, float], polar_deg: tuple[float, float],
              azimuth_deg: tuple[float, float]) -> np.ndarray:
    """A point on a spherical shell, uniform in area over the polar and azimuth band (cos of the polar angle
    uniform)."""
    r = _uniform(rng, radius)
    cos_lo, cos_hi = np.cos(np.radians(polar_deg[1])), np.cos(np.radians(polar_deg[0]))
    ct = rng.uniform(cos_lo, cos_hi)
    st = np.sqrt(max(0.0, 1 - ct * ct))
    az_lo, az_hi = np.radians(azimuth_deg)
    phi = az_lo + (az_hi - az_lo) * rng.random()  # = rng.uniform(0, 2 pi) for the default: same stream
    return r * np.array([st * np.cos(phi), st * np.sin(phi), ct])


def material_keys_check(model: ObjectModel) -> None:
    """Raise SimError (naming part and material) for a material Mitsuba does not know or a bad finish. Loads
    each BSDF once with Mitsuba (cheap), so this runs before any rendering."""
    import mitsuba as mi

    for part in model.parts:
        if part.material not in model.materials:
            raise SimError(f"object {model.name!r}: part {part.name!r} uses material {part.material!r}, "
                           f"which is not in its material map ({', '.join(model.materials)})")
    for key, spec in model.materials.items():
        if "type" not in spec:
            raise SimError(f"object {model.name!r}: material {key!r} has no 'type' (a Mitsuba BSDF name)")
        if spec.get("finish", "either") not in FINISHES:
            raise SimError(f"object {model.name!r}: material {key!r} finish {spec['finish']!r} is not one of "
                           f"{', '.join(FINISHES)}")
        example = bsdf_dict({**fixed_params(spec), "colour": [0.5, 0.5, 0.5], "alpha": 0.1})
        try:
            mi.load_dict(example)
        except Exception as exc:
            msg = str(exc).split(": ", 1)[-1] if ": " in str(exc) else str(exc)
            raise SimError(f"object {model.name!r}: material {key!r} ({spec}) is not a Mitsuba BSDF Mitsuba can "
                           f"make: {msg}") from None


def fixed_params(spec: dict) -> dict:
    """The material spec without the keys this module interprets (finish)."""
    return {k: v for k, v in spec.items() if k != "finish"}


def sample_material(rng: np.random.Generator, spec: dict, cfg: SceneConfig) -> dict:
    """Sampled parameters of one material: the spec's fixed params plus ``colour`` (RGB) and ``alpha``."""
    out = fixed_params(spec)
    out["colour"] = [_uniform(rng, cfg.colour) for _ in range(3)]
    finish = spec.get("finish", "either")
    if finish == "either":
        finish = "rough" if rng.random() < 0.5 else "smooth"
    out["finish"] = finish
    out["alpha"] = _uniform(rng, cfg.alpha_rough if finish == "rough" else cfg.alpha_smooth)
    return out


def ggx_lobes(materials: dict[str, dict]) -> dict[str, dict]:
    """Sampled materials with every microfacet lobe (``ALPHA_TYPES``) GGX, unless the material names its own."""
    return {k: {"distribution": "ggx", **m} if m["type"] in ALPHA_TYPES else m for k, m in materials.items()}


def bsdf_dict(m: dict) -> dict:
    """Sampled material params -> a Mitsuba BSDF dict (colour and alpha only where the type takes them)."""
    t = m["type"]
    d = {k: v for k, v in m.items() if k not in ("colour", "alpha", "finish")}
    if t in COLOUR_PARAM and "colour" in m:
        d[COLOUR_PARAM[t]] = {"type": "rgb", "value": list(m["colour"])}
    if t in ALPHA_TYPES and "alpha" in m:
        d["alpha"] = float(m["alpha"])
    return d


def rotation_z(yaw_rad: float) -> np.ndarray:
    c, s = np.cos(yaw_rad), np.sin(yaw_rad)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])


def object_to_world(pose: dict) -> np.ndarray:
    """4x4 transform of a sampled pose: stable resting transform, then yaw about z, then (x, y) shift."""
    t = rotation_z(pose["yaw_rad"]) @ np.asarray(pose["rest_transform"])
    t[:2, 3] += pose["xy_m"]
    return t


def _up_for(forward: np.ndarray) -> list[float]:
    """World z as the image's up direction, unless the camera looks almost straight down."""
    f = forward / np.linalg.norm(forward)
    return [0.0, 0.0, 1.0] if abs(f[2]) < 0.999 else [0.0, 1.0, 0.0]


def part_centre(model: ObjectModel, pose: dict) -> np.ndarray:
    """(3,) world metres: the centre of the posed part's bounding box, where the cameras aim (before jitter)."""
    to_world = object_to_world(pose)
    verts = np.concatenate([p.vertices for p in model.parts])
    world = verts @ to_world[:3, :3].T + to_world[:3, 3]
    return 0.5 * (world.min(0) + world.max(0))


def camera_dict(origin: np.ndarray, target: np.ndarray, cfg: SceneConfig, roll_deg: float = 0.0) -> dict[str, Any]:
    """A scene's ``camera`` entry: origin and target (world metres), up, and the lens's horizontal field of view;
    the up direction turned ``roll_deg`` about the optical axis (``SceneConfig.camera_roll_deg``'s sign)."""
    fov_deg = float(np.degrees(2 * np.arctan(cfg.sensor_width_mm / 2 / cfg.focal_length_mm)))
    up = _up_for(target - origin)
    if roll_deg:  # Rodrigues about the viewing direction; up is perpendicular to it after look_at's projection
        f = (target - origin) / np.linalg.norm(target - origin)
        u = np.asarray(up, np.float64) - f * float(np.dot(up, f))
        u /= np.linalg.norm(u)
        a = math.radians(roll_deg)
        up = (u * math.cos(a) + np.cross(f, u) * math.sin(a)).tolist()
    return {"origin": origin.tolist(), "target": target.tolist(), "up": up, "fov_x_deg": fov_deg}


VIEW_CAMERA_KEYS = ("camera_radius_m", "camera_polar_deg", "camera_azimuth_deg")
"""``[view]`` keys that are the scene's own camera ranges (``SceneConfig``), for the second camera."""

FLAT_DOME_BOTTOM_M = 5e-4
"""Height of the flat dome's lower edge above the belt (clear of the ground plane's own surface)."""


@dataclass(frozen=True)
class FlatDome:
    """A flat dome in front of a second camera (``[view] flat_dome_*``): a diffuse panel facing the part that the
    camera looks through, as a flat-dome light (or a large coaxial one) is built, modelled as a one-sided area
    emitter of ``radiance`` on a rectangle with a null BSDF. It stands ``distance_m`` from the part's centre toward
    the camera (horizontally), ``width_m`` wide, from ``FLAT_DOME_BOTTOM_M`` above the belt to ``top_m``. A
    camera at belt level looking square at a vertical front face sees the face mirror the camera's own side, so the
    face shows the dome (bright field): a dent's slope or a scratch's roughness sends its mirror image off the dome
    and it reads dark. A face turned by theta against the camera's line of sight (the part's yaw less the camera's
    azimuth) mirrors a direction 2 theta away, and a point of the face x off its centre mirrors that direction from
    x: the whole face stays in bright field while width / 2 >= x_end + distance tan(2 theta_max + its view angle),
    with some degrees more for a rough finish's lobe (``sim/presets/side-view.toml`` works it out for the line).

    ``fringe_period_m`` > 0 puts stripes across the dome's width (deflectometry, as ``SceneConfig``'s
    ``ring_fringe_*`` for the bright-field panel): its radiance times ``1 + fringe_depth * cos(2 pi x / period +
    phase)``, x metres across the dome from its edge at u = 0 of the rectangle (``flat_dome_dict``), phase
    ``fringe_phase_deg``. A face's slope t turns its mirror image by 2 t, which moves across the dome by about
    ``distance_m * tan(2 t)``; a whole number of periods across ``width_m`` keeps the dome's mean radiance."""

    radiance: float
    distance_m: float = 0.30
    width_m: float = 0.36
    top_m: float = 0.03
    fringe_period_m: float = 0.0
    fringe_depth: float = 0.5
    fringe_phase_deg: float = 0.0

    def __post_init__(self) -> None:
        for key in ("radiance", "distance_m", "width_m"):
            v = getattr(self, key)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise SimError(f"flat_dome_{key}: must be a number > 0, got {v!r}")
        if not (isinstance(self.top_m, (int, float)) and self.top_m > FLAT_DOME_BOTTOM_M):
            raise SimError(f"flat_dome_top_m: must be above {FLAT_DOME_BOTTOM_M:g} m, got {self.top_m!r}")
        for key, lo, hi in (("fringe_period_m", 0.0, math.inf), ("fringe_depth", 0.0, 1.0),
                            ("fringe_phase_deg", -math.inf, math.inf)):
            v = getattr(self, key)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and lo <= v <= hi):
                raise SimError(f"flat_dome_{key}: must be a number in [{lo:g}, {hi:g}], got {v!r}")

    def placed(self, centre: np.ndarray, toward_camera: np.ndarray) -> dict[str, Any]:
        """The scene's ``flat_dome`` entry for a part centred at ``centre`` (world metres) seen from the horizontal
        unit direction ``toward_camera``: the rectangle's centre, its facing (toward the part), size and radiance."""
        mid = 0.5 * (self.top_m + FLAT_DOME_BOTTOM_M)
        at = np.array([centre[0], centre[1], mid]) + self.distance_m * toward_camera
        return {"centre": at.tolist(), "toward": (-toward_camera).tolist(), "width_m": self.width_m,
                "height_m": self.top_m - FLAT_DOME_BOTTOM_M, "radiance": self.radiance,
                **({"fringe": [self.fringe_period_m, self.fringe_depth, self.fringe_phase_deg]}
                   if self.fringe_period_m else {})}  # earlier records unchanged without stripes


@dataclass(frozen=True)
class ViewConfig:
    """A second camera of the station (``[view]``): ``scene`` holds its camera ranges (``VIEW_CAMERA_KEYS``, the
    rest as the line's scene). With ``height_m`` (``camera_height_m``, metres above the belt) the camera stands at
    that height, ``camera_radius_m`` from the part's centre horizontally, and looks level at the part (its polar
    range is not used); else it is drawn on the shell as the line camera is. ``flat_dome``: a light it looks
    through (``FlatDome``), or None."""

    scene: SceneConfig
    height_m: tuple[float, float] | None = None
    flat_dome: FlatDome | None = None

    def __post_init__(self) -> None:
        h = self.height_m
        if h is not None and not (len(h) == 2 and all(isinstance(v, (int, float)) and math.isfinite(v) for v in h)
                                  and 0 < h[0] <= h[1]):
            raise SimError(f"camera_height_m: need a range (lo, hi) of metres above the belt, 0 < lo <= hi; "
                           f"got {h!r}")
        if self.flat_dome and self.flat_dome.distance_m >= self.scene.camera_radius_m[0]:
            raise SimError(f"flat_dome_distance_m: the camera looks through the dome, so it stands nearer the "
                           f"part than the camera ({self.scene.camera_radius_m[0]} m); got {self.flat_dome.distance_m}")

    @classmethod
    def from_dict(cls, view: dict[str, Any], scene: SceneConfig) -> ViewConfig:
        """``[view]``'s keys over the line's ``scene``; SimError names a bad key."""
        cameras = {k: v for k, v in view.items() if k in VIEW_CAMERA_KEYS}
        dome = {k.removeprefix("flat_dome_"): v for k, v in view.items() if k.startswith("flat_dome_")}
        if dome and "radiance" not in dome:
            raise SimError("flat_dome_radiance: the flat dome's other keys need its radiance")
        height = view.get("camera_height_m")
        return cls(SceneConfig.from_dict({**scene.to_dict(), **cameras}),
                   None if height is None else tuple(height), FlatDome(**dome) if dome else None)


def second_view(params: dict[str, Any], view: ViewConfig, model: ObjectModel,
                rng: np.random.Generator) -> dict[str, Any]:
    """The scene ``params`` seen by another camera of the same station: the same part, pose, defect, light and
    materials; the camera drawn from ``view``'s ranges on ``rng`` about the part's centre (on the shell, or at belt
    level: ``ViewConfig``) and aimed at the line camera's target, with ``view``'s flat dome placed before it. The
    line camera's entry is kept as ``line_camera``."""
    cfg = view.scene
    centre = part_centre(model, params["pose"])
    if view.height_m is None:
        cam = centre + _on_shell(rng, cfg.camera_radius_m, cfg.camera_polar_deg, cfg.camera_azimuth_deg)
    else:
        r, az = _uniform(rng, cfg.camera_radius_m), math.radians(_uniform(rng, cfg.camera_azimuth_deg))
        cam = np.array([centre[0] + r * math.cos(az), centre[1] + r * math.sin(az), _uniform(rng, view.height_m)])
    out = {**params, "camera": camera_dict(cam, np.asarray(params["camera"]["target"]), cfg),
           "line_camera": params["camera"]}
    if view.flat_dome is not None:
        toward = np.array([cam[0] - centre[0], cam[1] - centre[1], 0.0])
        out["flat_dome"] = view.flat_dome.placed(centre, toward / np.linalg.norm(toward))
    return out


def sample_scene(rng: np.random.Generator, cfg: SceneConfig, model: ObjectModel) -> dict[str, Any]:
    """Draw every scene parameter (JSON-serialisable): pose, camera, light, materials, background."""
    transforms, probs = stable_poses(model)
    k = int(rng.choice(len(probs), p=probs))  # drawn even when fixed, so every later draw is the same
    if cfg.rest_pose >= 0:
        if cfg.rest_pose >= len(probs):
            raise SimError(f"scene.rest_pose: {cfg.rest_pose}, but object {model.name!r} has {len(probs)} stable "
                           f"poses (0..{len(probs) - 1})")
        k = cfg.rest_pose
    yaw_lo, yaw_hi = np.radians(cfg.yaw_deg)  # lo + (hi - lo) U: rng.uniform(0, 2 pi)'s draw for the default
    pose = {"index": k, "probability": float(probs[k]), "rest_transform": transforms[k].tolist(),
            "yaw_rad": float(yaw_lo + (yaw_hi - yaw_lo) * rng.random()),
            "xy_m": [float(x) for x in rng.uniform(-cfg.object_xy_m, cfg.object_xy_m, 2)]}
    centre = part_centre(model, pose)
    target = centre + rng.uniform(-cfg.camera_target_jitter_m, cfg.camera_target_jitter_m, 3)
    cam = centre + _on_shell(rng, cfg.camera_radius_m, cfg.camera_polar_deg, cfg.camera_azimuth_deg)
    light = centre + _on_shell(rng, cfg.light_radius_m, cfg.light_polar_deg, cfg.light_azimuth_deg)
    materials = {key: sample_material(rng, spec, cfg) for key, spec in model.materials.items()}
    bg_kind = str(rng.choice(list(cfg.backgrounds)))
    bg_colour = cfg.colour if cfg.background_colour is None else cfg.background_colour
    # pplastic, not roughplastic: Mitsuba's roughplastic leaves light unpolarized in polarized variants (S1 = S2 = 0
    # on 99.8 % of the ground in renderer version 1) and its constructor precomputes tables (55 ms per sample)
    background = {
        "kind": bg_kind,
        "material": sample_material(rng, {"type": str(rng.choice(list(BACKGROUND_MATERIALS))), "finish": "rough"},
                                    replace(cfg, colour=bg_colour)),
        "colour2": [_uniform(rng, bg_colour) for _ in range(3)],
        "scale": float(rng.uniform(5, 60)),  # checker squares / noise blobs per metre... per plane side
        "noise_seed": int(rng.integers(2**31)),
    }
    return {
        "pose": pose,
        "camera": camera_dict(cam, target, cfg, cfg.camera_roll_deg),
        "light": {"origin": light.tolist(), "target": centre.tolist(), "intensity": _uniform(rng, cfg.light_intensity),
                  "cutoff_deg": cfg.light_cutoff_deg},
        "ambient_radiance": cfg.ambient_radiance,
        **({"ambient_gradient": cfg.ambient_gradient} if cfg.ambient_gradient else {}),  # older sets lack it
        **({"ambient_gradient_azimuth_deg": cfg.ambient_gradient_azimuth_deg}
           if cfg.ambient_gradient and cfg.ambient_gradient_azimuth_deg else {}),
        **({"ring_radiance": cfg.ring_radiance, "ring_elevation_deg": list(cfg.ring_elevation_deg)}
           if cfg.ring_radiance else {}),
        **({"ring_azimuth_deg": list(cfg.ring_azimuth_deg)}
           if cfg.ring_radiance and tuple(cfg.ring_azimuth_deg) != FULL_RING else {}),  # older sets lack it
        **({"ring_fringe": [cfg.ring_fringe_period_deg, cfg.ring_fringe_depth,
                            *([cfg.ring_fringe_phase_deg] if cfg.ring_fringe_phase_deg else [])]}
           if cfg.ring_fringe_period_deg else {}),  # SceneConfig refuses fringes without a ring
        **({"front_light": {"radiance": cfg.front_light_radiance, "span_m": list(cfg.front_light_span_m),
                            "width_m": cfg.front_light_width_m, "azimuth_deg": cfg.front_light_azimuth_deg}}
           if cfg.front_light_radiance else {}),
        "materials": materials,
        "background": background,
    }


def camera_axes(camera: dict) -> np.ndarray:
    """3x3 matrix whose rows are the project's camera axes in world coordinates: x image right, y image up,
    z toward the camera. ``world_normal @ camera_axes(cam).T`` gives camera-coordinate normals."""
    o, t, up = (np.asarray(camera[k], dtype=np.float64) for k in ("origin", "target", "up"))
    forward = (t - o) / np.linalg.norm(t - o)
    left = np.cross(up, forward)  # Mitsuba's look_at x axis (image left)
    left /= np.linalg.norm(left)
    cam_up = np.cross(forward, left)
    return np.stack([-left, cam_up, -forward])


def pose_parts(model: ObjectModel, to_world: np.ndarray) -> list[Part]:
    """The model's parts with vertices and normals in world coordinates."""
    r, t = to_world[:3, :3], to_world[:3, 3]
    out = []
    for p in model.parts:
        v = (p.vertices.astype(np.float64) @ r.T + t).astype(np.float32)
        n = (p.normals.astype(np.float64) @ r.T).astype(np.float32)
        out.append(Part(p.name, v, p.faces, n, p.material, p.tags))
    return out


def mesh_shape(part: Part, bsdf: dict | None):
    """An in-memory ``mi.Mesh`` of a (world-space) part, with its BSDF."""
    import mitsuba as mi

    props = mi.Properties()
    if bsdf is not None:
        props["bsdf"] = mi.load_dict(bsdf)
    mesh = mi.Mesh(part.name, len(part.vertices), len(part.faces), props, has_vertex_normals=True)
    params = mi.traverse(mesh)
    for key, values, dtype in (("vertex_positions", part.vertices, np.float32), ("faces", part.faces, np.uint32),
                               ("vertex_normals", part.normals, np.float32)):
        # the buffer's own type: mi.Float on the JIT variants, a dynamic scalar array on the scalar fallback
        params[key] = type(params[key])(np.ascontiguousarray(values, dtype=dtype).ravel())
    params.update()
    return mesh


def _noise_bitmap(seed: int, scale: float, c1: list[float], c2: list[float], res: int = 128) -> np.ndarray:
    """Smooth value noise (bilinear-upsampled random grid) blending two colours, (res, res, 3) float32."""
    import cv2

    rng = np.random.default_rng(seed)
    cells = int(np.clip(scale / 4, 2, res // 2))
    grid = rng.random((cells, cells)).astype(np.float32)
    t = cv2.resize(grid, (res, res), interpolation=cv2.INTER_CUBIC).clip(0, 1)[..., None]
    return (np.asarray(c1, np.float32) * (1 - t) + np.asarray(c2, np.float32) * t).astype(np.float32)


def background_shape(bg: dict, size_m: float) -> dict:
    """The ground plane (z = 0, ``size_m`` wide) with its procedural texture."""
    import mitsuba as mi

    mat = dict(bg["material"])
    bsdf = bsdf_dict(mat)
    param = COLOUR_PARAM[mat["type"]]
    if bg["kind"] == "checkerboard":
        s = bg["scale"]
        bsdf[param] = {"type": "checkerboard", "color0": {"type": "rgb", "value": mat["colour"]},
                       "color1": {"type": "rgb", "value": bg["colour2"]},
                       "to_uv": mi.ScalarTransform4f().scale([s, s, 1])}
    elif bg["kind"] == "noise":
        img = _noise_bitmap(bg["noise_seed"], bg["scale"], mat["colour"], bg["colour2"])
        bsdf[param] = {"type": "bitmap", "bitmap": mi.Bitmap(img), "filter_type": "bilinear"}
    return {"type": "rectangle", "to_world": mi.ScalarTransform4f().scale([size_m / 2, size_m / 2, 1]), "bsdf": bsdf}


SAMPLER = "multijitter"
"""Pixel sampler. Correlated multi-jittered samples halve the DoLP error of ``independent`` at 16 spp on the brick
scenes (with ``emitter_weights``) at the same cost, and, unlike ``stratified``/``ldsampler``, take any spp."""


def sampler_spp(spp: int) -> int:
    """The sample count ``SAMPLER`` really takes for ``spp``: an x-by-y grid with y = floor(sqrt(spp)) and
    x = ceil(spp / y) (Mitsuba rounds up, with a warning: 32 -> 35, 10 -> 12; 1, 2, 4, 8, 9, 12, 16 stay)."""
    y = math.isqrt(max(int(spp), 1))
    return y * -(-int(spp) // y)


def sensor_dict(camera: dict, width: int, height: int, spp: int, window: tuple[int, int, int, int] | None = None
                ) -> dict:
    """The perspective camera. ``window`` = (x0, y0, w, h): render only that block of the ``width`` x ``height``
    image (pixels, x0/y0 from the top-left), as a w x h film whose pixels are the full image's (same pitch, same
    rays, up to the sampler's jitter): the field of view narrows to the window and the principal point moves to
    its centre. Unlike the film's own crop (whose offset Dr.Jit bakes into the kernel, ~0.6 s of compilation per
    new offset), the field of view and principal point are opaque parameters: every window of one size shares a
    kernel."""
    import mitsuba as mi

    fov, w, h, extra = camera["fov_x_deg"], width, height, {}
    if window is not None:
        x0, y0, w, h = (int(v) for v in window)
        if w < 1 or h < 1 or x0 < 0 or y0 < 0 or x0 + w > width or y0 + h > height:
            raise SimError(f"render window {window} is not inside the {width}x{height} image")
        fov = float(np.degrees(2 * np.arctan(w / width * np.tan(np.radians(fov) / 2))))
        # offsets in units of the window's size; Mitsuba's image x runs right, the offset's y runs up
        extra = {"principal_point_offset_x": (x0 + w / 2 - width / 2) / w,
                 "principal_point_offset_y": (y0 + h / 2 - height / 2) / h}
    return {
        "type": "perspective", "fov": fov, "fov_axis": "x",
        "near_clip": 0.01, "far_clip": 100.0, **extra,
        "to_world": mi.ScalarTransform4f().look_at(origin=camera["origin"], target=camera["target"], up=camera["up"]),
        "film": {"type": "hdrfilm", "width": w, "height": h, "rfilter": {"type": "box"},
                 "pixel_format": "luminance", "sample_border": False},
        "sampler": {"type": SAMPLER, "sample_count": spp},
    }


def emitter_weights(params: dict) -> tuple[float, float]:
    """Light-sampling weights (spot, ambient): each emitter's irradiance scale on the object, spot ``I / d**2``
    (W/m^2 at the target) and ambient ``pi * L``. Mitsuba otherwise picks every emitter with equal probability,
    so half of all shadow rays go to the faint ambient light and the spot's light (nearly all of the signal) is
    sampled half as often. Unbiased either way: the weights change the noise, not the expected image."""
    light = params["light"]
    d2 = float(np.sum((np.asarray(light["origin"]) - np.asarray(light["target"])) ** 2))
    ring = params.get("ring_radiance", 0.0)
    ring_e = ring * ring_irradiance_factor(*params["ring_elevation_deg"],
                                           *params.get("ring_azimuth_deg", FULL_RING)) if ring else 0.0
    return float(light["intensity"]) / max(d2, 1e-6), float(np.pi * params["ambient_radiance"] + ring_e)


def ring_irradiance_factor(lo_deg: float, hi_deg: float, az_lo_deg: float = 0.0, az_hi_deg: float = 360.0) -> float:
    """Irradiance on a horizontal face per unit radiance of a ring at elevations ``[lo_deg, hi_deg]`` covering
    azimuths ``[az_lo_deg, az_hi_deg]``: ``pi (cos^2 lo - cos^2 hi)`` times the sector's share of the circle
    (W/m^2 per W/(m^2 sr))."""
    lo, hi = np.radians(lo_deg), np.radians(hi_deg)
    return float(np.pi * (np.cos(lo) ** 2 - np.cos(hi) ** 2) * (az_hi_deg - az_lo_deg) / 360.0)


GRADIENT_ROWS = 64
"""Rows of the gradient dome's envmap (a smooth cosine: 64 rows are within 0.1 % of it)."""


def ambient_dict(radiance: float, gradient: float, azimuth_deg: float = 0.0) -> dict:
    """The environment light (``SceneConfig.ambient_radiance``, ``ambient_gradient``,
    ``ambient_gradient_azimuth_deg``): Mitsuba's constant emitter when uniform, else an envmap whose rows run along
    its local +y, turned about world z so that local +y points ``azimuth_deg`` from world +x toward +y."""
    import mitsuba as mi

    if not gradient:
        return {"type": "constant", "radiance": {"type": "spectrum", "value": radiance}}
    theta = (np.arange(GRADIENT_ROWS) + 0.5) / GRADIENT_ROWS * np.pi  # from the envmap's +y
    rows = (1.0 + gradient * np.cos(theta)).astype(np.float32)
    bitmap = mi.Bitmap(np.repeat(rows[:, None, None], 2 * GRADIENT_ROWS, 1))
    return {"type": "envmap", "bitmap": bitmap, "scale": radiance,
            "to_world": mi.ScalarTransform4f().rotate(axis=[0, 0, 1], angle=azimuth_deg - 90)}


RING_ROWS = 720
"""Rows of the ring light's envmap (a quarter of a degree each); a row the ring's edge cuts gets its covered share.
A sector (``SceneConfig.ring_azimuth_deg``) has twice as many columns, a quarter of a degree each as well."""


def _covered(edges: np.ndarray, lo: float, hi: float, period: float | None = None) -> np.ndarray:
    """Share of each cell between consecutive ``edges`` (increasing) that lies in ``[lo, hi]``; with ``period``,
    of ``[lo, hi]`` repeated every ``period`` (edges and interval within two periods of each other)."""
    shifts = tuple(k * period for k in (-2, -1, 0, 1, 2)) if period else (0.0,)
    inside = sum(np.clip(np.minimum(edges[1:], hi + k) - np.maximum(edges[:-1], lo + k), 0, None) for k in shifts)
    return inside / np.diff(edges)


def ring_dict(radiance: float, ring: float, elevation_deg: Sequence[float],
              azimuth_deg: Sequence[float] = FULL_RING, fringe: Sequence[float] = (0.0, 0.0),
              gradient: float = 0.0, gradient_azimuth_deg: float = 0.0) -> dict:
    """The environment with a ring light (``SceneConfig.ring_radiance``): uniform ``radiance`` from every direction
    plus ``ring`` at elevations ``elevation_deg`` (lo, hi) above the ground and azimuths ``azimuth_deg`` (lo, hi;
    degrees from world +x toward +y), as an envmap whose pole (its local +y) is world +z, so its rows are polar
    angles from the vertical. Mitsuba reads a direction's column as ``u = atan2(x, -z) / 2 pi`` in the map's
    frame, which is world azimuth ``phi = 90 - 360 u`` degrees here (a test checks a sector's side). ``fringe`` =
    (period in degrees, depth[, phase in degrees, default 0]): each row of the ring times ``1 + depth cos(2 pi (e -
    elevation_deg[0]) / period + phase)`` at its centre's elevation e (``SceneConfig.ring_fringe_period_deg``);
    period 0: uniform. ``gradient`` (g) and
    ``gradient_azimuth_deg`` make the dome a gradient dome as ``ambient_dict`` does (``radiance`` (1 + g w_a), w_a
    the direction's component along that azimuth, at each cell's centre), so a segment of the dome and the ring
    share the one environment map."""
    import mitsuba as mi

    edges = np.linspace(0.0, 180.0, RING_ROWS + 1)  # polar angle of the rows' edges, degrees
    rows = _covered(edges, 90.0 - float(elevation_deg[1]), 90.0 - float(elevation_deg[0]))
    period, depth, phase = (float(v) for v in (*fringe, 0.0)[:3])
    if period:
        elevation = 90.0 - 0.5 * (edges[:-1] + edges[1:])
        rows = rows * (1.0 + depth * np.cos(2 * np.pi * (elevation - float(elevation_deg[0])) / period
                                            + math.radians(phase)))
    # columns run along u, i.e. toward decreasing azimuth: column j covers phi in [90 - 360 (j+1)/W, ...]
    u_edges = np.linspace(0.0, 1.0, 2 * RING_ROWS + 1)
    phi_edges = 90.0 - 360.0 * u_edges[::-1]  # increasing; reversed back to column order below
    if tuple(azimuth_deg) == FULL_RING:  # a uniform ring needs columns only for a gradient dome
        cols = np.ones(2 * RING_ROWS if gradient else 4)
    else:
        cols = _covered(phi_edges, float(azimuth_deg[0]), float(azimuth_deg[1]), period=360.0)[::-1]
    cells = rows[:, None] * cols[None, :]
    dome = float(radiance)
    if gradient:
        polar = np.radians(0.5 * (edges[:-1] + edges[1:]))[:, None]
        phi = np.radians(0.5 * (phi_edges[:-1] + phi_edges[1:])[::-1])[None, :]
        dome = radiance * (1.0 + gradient * np.sin(polar) * np.cos(phi - math.radians(gradient_azimuth_deg)))
    bitmap = mi.Bitmap((dome + ring * cells).astype(np.float32)[..., None])
    return {"type": "envmap", "bitmap": bitmap, "scale": 1.0,
            "to_world": mi.ScalarTransform4f().rotate(axis=[1, 0, 0], angle=90)}


FRONT_LIGHT_HEIGHT_M = 2e-4
"""Height of the front light's strip above the belt (clear of the ground plane's own surface)."""

FRONT_LIGHT_SAMPLING = 0.3
"""The front light's light-sampling weight per unit of pi L (``emitter_weights``' units): about the share of a whole
plane's irradiance that the part's faces get from the strip on average (a front face 0.14-0.33, the top face none).
Measured on two parts of seed 919 at 16 spp (pixel noise as a share of the face's brightness; without the strip
top face 8 %, front face 16-17 %): at 1.0 the strip draws most light samples and the top face's noise is 13-15 %,
at 0.3 top 10-12 % and front 17-18 %, at 0.15 top 9-10 % but front 20 %. A weight changes the noise, not the
expected image."""


def front_light_dict(light: dict) -> dict:
    """The front light (``SceneConfig.front_light_*``, as ``sample_scene`` stores them under ``front_light``): a
    rectangle facing up, ``FRONT_LIGHT_HEIGHT_M`` above the belt, from ``span_m[0]`` to ``span_m[1]`` metres from
    the world origin toward ``azimuth_deg`` and ``width_m`` across, with a black BSDF and an area emitter of
    ``radiance``. Its light-sampling weight is ``FRONT_LIGHT_SAMPLING`` pi L."""
    import mitsuba as mi

    near, far = (float(v) for v in light["span_m"])
    az = math.radians(float(light["azimuth_deg"]))
    centre = 0.5 * (near + far) * np.array([math.cos(az), math.sin(az)])
    to_world = (mi.ScalarTransform4f().translate([float(centre[0]), float(centre[1]), FRONT_LIGHT_HEIGHT_M])
                @ mi.ScalarTransform4f().rotate(axis=[0, 0, 1], angle=float(light["azimuth_deg"]) - 270.0)
                @ mi.ScalarTransform4f().scale([float(light["width_m"]) / 2, (far - near) / 2, 1.0]))
    return {"type": "rectangle", "to_world": to_world,
            "bsdf": {"type": "diffuse", "reflectance": {"type": "spectrum", "value": 0.0}},
            "emitter": {"type": "area", "radiance": {"type": "spectrum", "value": float(light["radiance"])},
                        "sampling_weight": float(FRONT_LIGHT_SAMPLING * np.pi * light["radiance"])}}


def flat_dome_dict(dome: dict) -> dict:
    """The flat dome (``FlatDome.placed``'s entry): a rectangle with a null BSDF, which the camera's rays pass
    through, and a one-sided area emitter of ``radiance`` facing ``toward`` (the part): the camera behind it sees
    its unlit back. Its light-sampling weight is its irradiance on a face square to it, radiance times its solid
    angle from the fixture's centre (the world origin; ``emitter_weights``' units). The mask passes must not see it
    (``sim.render.render_sample`` renders them without it). With ``fringe`` (period in metres, depth, phase in
    degrees: ``FlatDome``'s stripes) the radiance is a texture of ``FLAT_DOME_FRINGE_COLUMNS`` columns across the
    width (u), each at its centre's x; the weight keeps the mean radiance."""
    import mitsuba as mi

    c, toward = np.asarray(dome["centre"], float), np.asarray(dome["toward"], float)
    w, h, radiance = float(dome["width_m"]), float(dome["height_m"]), float(dome["radiance"])
    frame = mi.ScalarTransform4f().look_at(origin=c.tolist(), target=(c + toward).tolist(), up=[0, 0, 1])
    texture: dict[str, Any] = {"type": "spectrum", "value": radiance}
    if dome.get("fringe"):
        period, depth, phase = (float(v) for v in dome["fringe"])
        x = (np.arange(FLAT_DOME_FRINGE_COLUMNS) + 0.5) * w / FLAT_DOME_FRINGE_COLUMNS
        row = radiance * (1.0 + depth * np.cos(2 * np.pi * x / period + math.radians(phase)))
        texture = {"type": "bitmap", "bitmap": mi.Bitmap(row.astype(np.float32)[None, :, None]), "raw": True,
                   "filter_type": "bilinear", "wrap_mode": "clamp"}
    return {"type": "rectangle", "bsdf": {"type": "null"},
            "to_world": frame @ mi.ScalarTransform4f().scale([w / 2, h / 2, 1.0]),
            "emitter": {"type": "area", "radiance": texture,
                        "sampling_weight": radiance * w * h / float(np.linalg.norm(c[:2])) ** 2}}


FLAT_DOME_FRINGE_COLUMNS = 720
"""Columns of a striped flat dome's radiance texture (``flat_dome_dict``): 2 mm each on the preset's 0.36 m dome,
under a hundredth of the shortest period a screen would use (0.05 m and up)."""


def build_scene(params: dict, parts: list[Part], materials: dict[str, dict], width: int, height: int, spp: int,
                background_size_m: float = 1.0, lights: bool = True, window: tuple[int, int, int, int] | None = None
                ) -> tuple[dict, list[str]]:
    """Scene dict for ``mi.load_dict`` and the shape keys of ``parts`` in order. ``parts`` are in world
    coordinates; ``materials`` maps a part's material key to sampled material params. ``lights=False`` leaves
    out emitters, background texture and BSDFs (a geometry-only scene for mask passes)."""
    import mitsuba as mi

    scene: dict[str, Any] = {"type": "scene", "sensor": sensor_dict(params["camera"], width, height, spp, window)}
    keys = []
    for i, part in enumerate(parts):
        key = f"part{i:02d}_{part.name}"
        scene[key] = mesh_shape(part, bsdf_dict(materials[part.material]) if lights else None)
        keys.append(key)
    if lights:
        scene["ground"] = background_shape(params["background"], background_size_m)
        light = params["light"]
        spot_w, ambient_w = emitter_weights(params)
        scene["spot"] = {"type": "spot", "sampling_weight": spot_w,
                         "intensity": {"type": "spectrum", "value": light["intensity"]},
                         "cutoff_angle": light["cutoff_deg"], "beam_width": 0.75 * light["cutoff_deg"],
                         "to_world": mi.ScalarTransform4f().look_at(origin=light["origin"], target=light["target"],
                                                                    up=[0, 0, 1])}
        if params.get("ring_radiance"):
            scene["ambient"] = ring_dict(params["ambient_radiance"], params["ring_radiance"],
                                         params["ring_elevation_deg"], params.get("ring_azimuth_deg", FULL_RING),
                                         params.get("ring_fringe", (0.0, 0.0)), params.get("ambient_gradient", 0.0),
                                         params.get("ambient_gradient_azimuth_deg", 0.0))
        elif params["ambient_radiance"] > 0:
            scene["ambient"] = ambient_dict(params["ambient_radiance"], params.get("ambient_gradient", 0.0),
                                            params.get("ambient_gradient_azimuth_deg", 0.0))
        if "ambient" in scene:
            scene["ambient"]["sampling_weight"] = ambient_w
        if params.get("front_light"):
            scene["front_light"] = front_light_dict(params["front_light"])
        if params.get("flat_dome"):
            scene["flat_dome"] = flat_dome_dict(params["flat_dome"])
    else:
        scene["ground"] = {"type": "rectangle",
                           "to_world": mi.ScalarTransform4f().scale([background_size_m / 2, background_size_m / 2, 1])}
    return scene, keys
