"""Reading boomdyn results files (layout: docs/output.md).

Every loader returns None (or an empty container) when its part of the file
is absent, so that tools can work on files of failed or partial runs.
"""

from dataclasses import dataclass, field

import h5py
import numpy as np

ENERGY_COLUMNS = ("kinetic", "strain", "gravity potential", "total")
ANCF_COORDINATES_PER_NODE = 4  # x, y, dx/ds, dy/ds
SPATIAL_COORDINATES_PER_NODE = 7  # spatial ANCF beam: x, y, z, dx/ds, dy/ds, dz/ds, twist
STRAIN_COLUMNS = ("axial", "torsion", "curvature2", "curvature3")  # /frames/<name>/strains


def open_run(path):
    """The results file, opened read-only (usable as a context manager)."""
    return h5py.File(path, "r")


def _plain(value):
    """An attribute value as a plain Python object (str, int, float, list)."""
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    return value


def _strings(dataset):
    return [s.decode("utf-8") if isinstance(s, bytes) else str(s) for s in dataset[()]]


def _array(group, name):
    """Dataset `name` of `group` as an array, or None when it is missing or empty."""
    if group is None or name not in group:
        return None
    data = group[name][()]
    return data if np.size(data) > 0 else None


def attributes(f, path="/"):
    """The attributes of the object at `path` as a dict ({} if it is absent)."""
    if path not in f:
        return {}
    return {key: _plain(value) for key, value in f[path].attrs.items()}


def scene_name(f):
    return str(attributes(f).get("scene_name", "unnamed scene"))


def is_static(f):
    return attributes(f).get("analysis") == "static"


def dimension(f):
    """3 for a spatial scene, 2 for a planar one (files without /layout's attribute are planar)."""
    return int(attributes(f, "/layout").get("dimension", 2))


@dataclass
class Body:
    name: str
    first: int  # index of the first coordinate in q
    count: int  # number of coordinates
    dimension: int = 2  # 3 in a spatial scene

    @property
    def per_node(self):
        return SPATIAL_COORDINATES_PER_NODE if self.dimension == 3 else ANCF_COORDINATES_PER_NODE

    @property
    def is_beam(self):
        # The layout carries no body type: an ANCF beam is recognized by its
        # coordinates per node (4 planar, 7 spatial) and at least 2 nodes (a
        # rigid body has fewer: 3 planar, 7 spatial).
        return self.count >= 2 * self.per_node and self.count % self.per_node == 0

    def _nodes(self, q):
        q = np.asarray(q)
        block = q[..., self.first:self.first + self.count]
        return block.reshape(q.shape[:-1] + (self.count // self.per_node, self.per_node))

    def node_positions(self, q):
        """Nodal positions of this beam from q of shape (..., nq): shape (..., nodes, 2), spatial (..., nodes, 3)."""
        return self._nodes(q)[..., :self.dimension]

    def node_twists(self, q):
        """Twist coordinates (rad) of a spatial beam's nodes: shape (..., nodes). They are measured from
        reference triads that the beam may move (docs/model.md §1.7); /frames/<name>/twist is measured from
        the initial section."""
        return self._nodes(q)[..., 6]


@dataclass
class Constraint:
    name: str
    first_row: int
    num_rows: int


@dataclass
class Layout:
    nq: int
    nlambda: int
    bodies: list = field(default_factory=list)
    constraints: list = field(default_factory=list)
    dimension: int = 2

    def body(self, name):
        return next(b for b in self.bodies if b.name == name)


def load_layout(f):
    if "layout" not in f:
        return None
    g = f["layout"]
    dim = dimension(f)
    bodies, constraints = [], []
    if "body_names" in g:
        bodies = [Body(name, int(first), int(count), dim) for name, first, count in
                  zip(_strings(g["body_names"]), g["body_first_coordinate"][()], g["body_num_coordinates"][()])]
    if "constraint_names" in g:
        constraints = [Constraint(name, int(first), int(rows)) for name, first, rows in
                       zip(_strings(g["constraint_names"]), g["constraint_first_row"][()],
                           g["constraint_num_rows"][()])]
    return Layout(int(g.attrs.get("nq", 0)), int(g.attrs.get("nlambda", 0)), bodies, constraints, dim)


def load_steps(f):
    """{"time", "dt", "newton_iterations", "constraint_violation", "energy"}: whichever are present."""
    group = f.get("steps")
    names = ("time", "dt", "newton_iterations", "constraint_violation", "energy")
    steps = {name: _array(group, name) for name in names}
    return {name: data for name, data in steps.items() if data is not None}


def load_sensors(f):
    """{sensor name: {"position": (n, 2), "velocity": (n, 2)}} with whichever are present (spatial: (n, 3))."""
    sensors = {}
    for name, group in f.get("sensors", {}).items():
        series = {key: _array(group, key) for key in ("position", "velocity")}
        series = {key: data for key, data in series.items() if data is not None}
        if series:
            sensors[name] = series
    return sensors


def load_frames(f):
    """The sections of a spatial scene's frame sensors: {name: {"triad": (n, 3, 3) (column j is d_(j+1)),
    "twist": (n), "angular_velocity": (n, 3), "strains": (n, 4) (STRAIN_COLUMNS)}}, whichever are present."""
    frames = {}
    for name, group in f.get("frames", {}).items():
        series = {key: _array(group, key) for key in ("triad", "twist", "angular_velocity", "strains")}
        if series["triad"] is not None:
            series["triad"] = series["triad"].reshape(-1, 3, 3)
        series = {key: data for key, data in series.items() if data is not None}
        if series:
            frames[name] = series
    return frames


def load_polylines(f):
    """The sampled booms of /paraview: [(time, [polyline (points, 3), ...], {field: (points, ...)})], one
    entry per snapshot, the polylines split where the segments of one body end (docs/output.md)."""
    group = f.get("paraview")
    if group is None or "segments" not in group:
        return []
    segments = group["segments"][()]
    # A polyline ends where the next segment does not start at the previous one's end.
    starts = [0] + [k for k in range(1, len(segments)) if segments[k][0] != segments[k - 1][1]]
    ranges = [(segments[a][0], segments[b - 1][1] + 1) for a, b in zip(starts, starts[1:] + [len(segments)])]
    snapshots = []
    for key in sorted((k for k in group if k.isdigit()), key=int):
        g = group[key]
        points = g["points"][()]
        fields = {name: g[name][()] for name in g if name != "points" and not name.startswith("rope_")}
        snapshots.append((float(g.attrs.get("time", np.nan)), [points[a:b] for a, b in ranges], fields))
    return snapshots


def load_states(f):
    """{"time": (m), "q": (m, nq), "v": ..., "lambda": ...} or None without snapshots."""
    group = f.get("state")
    states = {name: _array(group, name) for name in ("time", "q", "v", "lambda")}
    if states["time"] is None or states["q"] is None:
        return None
    return {name: data for name, data in states.items() if data is not None}


def load_modal(f):
    """{"frequencies_hz": (k), "shapes": (k, nq) or None, "state_time": float or None} or None."""
    group = f.get("modal")
    frequencies = _array(group, "frequencies_hz")
    if frequencies is None:
        return None
    return {"frequencies_hz": frequencies, "shapes": _array(group, "shapes"),
            "state_time": _plain(group.attrs.get("state_time"))}


def load_summary(f):
    return attributes(f, "/summary")


def scene_text(f):
    """The scene file as run (/scene/text), or "" when absent."""
    if "scene/text" not in f:
        return ""
    text = f["scene/text"][()]
    return text.decode("utf-8") if isinstance(text, bytes) else str(text)


def load_scene(f):
    """The scene as a dict parsed from /scene/text, or None (no text, or no PyYAML:
    Debian's python3-yaml; the other readers here do not need it)."""
    text = scene_text(f)
    try:
        import yaml
    except ImportError:
        return None
    return yaml.safe_load(text) if text else None


def body_lengths(f):
    """{body name: undeformed length in m} from the scene text.

    Lengths are not in /layout. Without PyYAML the `length:` keys of the
    scene text are taken in order, one per body (the scene lists bodies
    first-to-last in model order and no other key is called `length`)."""
    layout = load_layout(f)
    names = [b.name for b in layout.bodies] if layout else []
    scene = load_scene(f)
    if scene is not None:
        return {b["name"]: float(b["length"]) for b in scene.get("bodies", [])}
    import re
    found = re.findall(r"(?<![\w])length:\s*([-+0-9.eE]+)", re.sub(r"#[^\n]*", "", scene_text(f)))
    if len(found) != len(names):
        raise ValueError("cannot tell the body lengths from /scene/text without PyYAML (python3-yaml)")
    return {name: float(value) for name, value in zip(names, found)}
