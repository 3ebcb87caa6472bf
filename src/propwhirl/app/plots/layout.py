"""Layout helpers of the figures with many modes: mode families and their colours, label text
that wraps, and labels placed without collision.

* :data:`FAMILY_COLOURS`, :data:`FAMILY_MAPS` — the colour and the hue of each mode family
  (the families are :func:`propwhirl.analysis.naming.mode_family`'s: from the name — the
  whirl sense — and the content — bending or torsion), the one table of them.
* :func:`family_shades` — one hue per family, graded shades within it (the emphasised modes
  of one family stay told apart, their family seen at a glance).
* :func:`place_labels` — annotations placed greedily, each at the nearest free spot around
  its anchor, measured with the renderer's text extents (no two label boxes overlap, every
  box inside its axes when there is room); a leader line joins a label moved off its anchor.
* :func:`end_labels`, :func:`stack_labels` — end labels of curves (a Campbell diagram)
  stacked in a column at least one text height apart, measured the same way.

The placement works in display coordinates of a laid-out figure: :func:`freeze_layout` draws
the figure once (the constrained layout settles the axes) and then switches the layout engine
off, so that the axes do not move after the labels were placed.
"""
from __future__ import annotations

import textwrap
from collections.abc import Sequence

import numpy as np

from propwhirl.app.plots.canvas import spread_labels

#: each family (:data:`propwhirl.analysis.naming.FAMILIES`, in the order of the legends)
#: with its hue (a matplotlib sequential colormap)
FAMILY_MAPS = {"wing bending": "Blues", "wing torsion": "Purples", "backward whirl": "Reds",
               "forward whirl": "Greens", "in-plane": "Oranges", "other": "Greys"}
#: the family's own colour (curves of the Campbell diagram, legends, thin lines): the colours
#: of every figure's families
FAMILY_COLOURS = {"wing bending": "tab:blue", "wing torsion": "tab:purple",
                  "backward whirl": "tab:red", "forward whirl": "tab:green",
                  "in-plane": "tab:orange", "other": "0.4"}
#: characters per line of a wrapped label
WRAP = 30
#: cost of moving a label one pixel from its anchor, against the area [px²] of curves it
#: covers (:func:`place_labels`): about 500 px of leader line for one curve across a label
DISTANCE_COST = 1.0


def family_shades(families: Sequence[str]) -> list:
    """A colour per entry: the family's hue, shades from dark to medium within a family in
    the order given (one member: the family's own colour)."""
    from matplotlib import colormaps

    count: dict[str, int] = {}
    for fam in families:
        count[fam] = count.get(fam, 0) + 1
    seen: dict[str, int] = {}
    out = []
    for fam in families:
        i = seen.get(fam, 0)
        seen[fam] = i + 1
        n = count[fam]
        if n == 1:
            out.append(FAMILY_COLOURS.get(fam, "0.4"))
            continue
        cmap = colormaps[FAMILY_MAPS.get(fam, "Greys")]
        out.append(cmap(0.95 - 0.5 * i / (n - 1)))
    return out


def wrap(text: str, width: int = WRAP) -> str:
    """`text` wrapped line by line at `width` characters (long mode names in a label)."""
    return "\n".join(textwrap.fill(line, width, break_long_words=False) or line
                     for line in text.split("\n"))


def freeze_layout(fig) -> None:
    """Draw `fig` once (its layout engine settles the axes), then switch the engine off so
    that labels placed in display coordinates stay where they were put."""
    fig.canvas.draw()
    fig.set_layout_engine("none")


def _overlaps(a, b, pad: float) -> bool:
    return not (a.x1 + pad <= b.x0 or b.x1 + pad <= a.x0
                or a.y1 + pad <= b.y0 or b.y1 + pad <= a.y0)


def _offsets(step_x: float, step_y: float, nx: int, ny: int,
             prefer: str) -> tuple[np.ndarray, np.ndarray]:
    """(M, 2) candidate offsets [points] around an anchor and (M,) their distances [points],
    nearest first: vertical distance counts 1.6 times, the side away from `prefer`
    ("below", "above", "right") three times."""
    i, j = np.meshgrid(np.arange(-nx, nx + 1), np.arange(-ny, ny + 1), indexing="ij")
    cand = np.column_stack([i.ravel() * step_x, j.ravel() * step_y])
    cand = cand[(i.ravel() != 0) | (j.ravel() != 0)]
    away = {"below": cand[:, 1] > 0, "above": cand[:, 1] < 0, "right": cand[:, 0] < 0}[prefer]
    dist = np.hypot(cand[:, 0], 1.6 * cand[:, 1]) * np.where(away, 3.0, 1.0)
    order = np.argsort(dist, kind="stable")
    return cand[order], dist[order]


def _areas(boxes: np.ndarray, obstacles: np.ndarray, pad: float) -> np.ndarray:
    """(M,) summed overlap areas [px²] of boxes (M, 4: x0, y0, x1, y1) with obstacles (N, 4),
    each obstacle grown by `pad`."""
    if obstacles.size == 0:
        return np.zeros(len(boxes))
    w = (np.minimum(boxes[:, None, 2], obstacles[None, :, 2] + pad)
         - np.maximum(boxes[:, None, 0], obstacles[None, :, 0] - pad))
    h = (np.minimum(boxes[:, None, 3], obstacles[None, :, 3] + pad)
         - np.maximum(boxes[:, None, 1], obstacles[None, :, 1] - pad))
    return (np.clip(w, 0.0, None) * np.clip(h, 0.0, None)).sum(axis=1)


def curve_boxes(ax, lines: Sequence, step_px: float = 3.0, size_px: float = 3.0) -> list:
    """Small boxes [display pixels] along the drawn part of `lines` of `ax` (every `step_px`
    along the path, inside the axes): obstacles that :func:`place_labels` keeps its labels
    off where it can."""
    from matplotlib.transforms import Bbox

    frame = ax.get_window_extent()
    out = []
    for ln in lines:
        xy = np.column_stack([np.asarray(ln.get_xdata(), float), np.asarray(ln.get_ydata(), float)])
        for seg in np.split(xy, np.flatnonzero(~np.isfinite(xy).all(axis=1))):
            seg = seg[np.isfinite(seg).all(axis=1)]
            if len(seg) == 0:
                continue
            d = ax.transData.transform(seg)
            step = np.hypot(*np.diff(d, axis=0).T) if len(d) > 1 else np.zeros(0)
            pts = [d[:1]] + [np.linspace(a, b, max(int(n / step_px), 1) + 1)[1:]
                             for a, b, n in zip(d[:-1], d[1:], step)]
            for x, y in np.concatenate(pts):
                if frame.x0 <= x <= frame.x1 and frame.y0 <= y <= frame.y1:
                    out.append(Bbox.from_bounds(x - 0.5 * size_px, y - 0.5 * size_px,
                                                size_px, size_px))
    return out


def place_labels(ax, anchors: Sequence[tuple[float, float]], texts: Sequence[str],
                 colours: Sequence, *, fontsize: float = 8.0, avoid: Sequence = (),
                 soft: Sequence = (), prefer: str = "below", gid: str = "label",
                 pad: float = 2.0, aligns: Sequence[str] | None = None) -> list:
    """Annotate `ax` at data points `anchors` with `texts`, no two boxes overlapping.

    The labels are placed in the order given (put the important ones first), each at the
    nearest offset of a grid around its anchor (steps of a quarter of a label width by half a
    label height, up to the whole axes; the `prefer`red side first) where its box, padded by
    `pad` pixels, lies inside the axes and overlaps no label placed before, no bounding box
    in `avoid` (display coordinates, e.g. markers) and whose leader crosses no label; among
    those, the spot of least covered area of `soft` (e.g. :func:`curve_boxes` of the
    curves that matter) plus :data:`DISTANCE_COST` × its distance.  Only where no spot is
    free of labels and `avoid`, the spot of least overlap.  A leader line joins each label to
    its anchor.  The figure's layout must be frozen (:func:`freeze_layout`).  `aligns`: each
    label's line alignment ("center" by default; "left" for a table).  Returns the
    annotations, with ``gid`` set.
    """
    fig = ax.figure
    renderer = fig.canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    hard = [tuple(b.extents) for b in avoid]
    n_avoid = len(hard)
    soft_arr = np.array([tuple(b.extents) for b in soft], dtype=float).reshape(-1, 4)
    out = []
    pts = fig.dpi / 72.0                        # pixels per point
    aligns = list(aligns) if aligns is not None else ["center"] * len(texts)
    for (x, y), text, colour, align in zip(anchors, texts, colours, aligns):
        ann = ax.annotate(text, xy=(x, y), xytext=(0.0, 0.0), textcoords="offset points",
                          fontsize=fontsize, color=colour, ha="center", va="center", gid=gid,
                          multialignment=align,
                          annotation_clip=False, zorder=6,
                          bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none",
                                    alpha=0.85),
                          arrowprops=dict(arrowstyle="-", color=colour, lw=0.6,
                                          shrinkA=0.0, shrinkB=3.0))
        box = _text_box(ann, renderer)                  # at offset 0: centred on the anchor
        nx = int(frame.width / max(0.25 * box.width, 1.0)) + 1
        ny = int(frame.height / max(0.5 * box.height, 1.0)) + 1
        off, dist = _offsets(0.25 * box.width / pts, 0.5 * box.height / pts, nx, ny, prefer)
        boxes = np.asarray(box.extents)[None, :] + np.tile(off * pts, 2)
        ok = ((boxes[:, 0] >= frame.x0) & (boxes[:, 2] <= frame.x1)
              & (boxes[:, 1] >= frame.y0) & (boxes[:, 3] <= frame.y1))
        dist = dist * pts                                # [px]
        if ok.any():
            off, boxes, dist = off[ok], boxes[ok], dist[ok]
        hard_arr = np.array(hard, dtype=float).reshape(-1, 4)
        labels_arr = np.array(hard[n_avoid:], dtype=float).reshape(-1, 4)
        anchor = ax.transData.transform((x, y))
        best, best_cost = 0, np.inf
        for c0 in range(0, len(off), 256):               # nearest first, in chunks
            chunk = boxes[c0:c0 + 256]
            cost = (1e6 * _areas(chunk, hard_arr, pad) + 1e3 * _crossings(anchor, chunk, labels_arr)
                    + _areas(chunk, soft_arr, 0.0) + DISTANCE_COST * dist[c0:c0 + 256])
            k = int(np.argmin(cost))
            if cost[k] < best_cost:
                best, best_cost = c0 + k, float(cost[k])
            if c0 + 256 < len(off) and DISTANCE_COST * dist[c0 + 256] > best_cost:
                break                                    # no farther spot can be better
        ann.xyann = (float(off[best, 0]), float(off[best, 1]))
        placed = _text_box(ann, renderer)
        hard.append(tuple(placed.extents))
        leader = np.linspace(anchor, (0.5 * (placed.x0 + placed.x1),
                                      0.5 * (placed.y0 + placed.y1)), 12)   # anchor → centre
        soft_arr = np.vstack([soft_arr, np.column_stack([leader - 1.5, leader + 1.5])])
        out.append(ann)
    return out


def _crossings(anchor: np.ndarray, boxes: np.ndarray, labels: np.ndarray) -> np.ndarray:
    """(M,) how many of 10 points along the leader from `anchor` to each box's centre lie
    inside a label already placed."""
    if labels.size == 0:
        return np.zeros(len(boxes))
    centre = 0.5 * (boxes[:, :2] + boxes[:, 2:])
    t = np.linspace(0.05, 0.95, 10)[None, :, None]
    p = anchor[None, None, :] + t * (centre[:, None, :] - anchor[None, None, :])   # (M, 10, 2)
    x, y = p[:, :, None, 0], p[:, :, None, 1]
    box = labels[None, None, :, :]
    inside = (x > box[..., 0]) & (x < box[..., 2]) & (y > box[..., 1]) & (y < box[..., 3])
    return inside.any(axis=2).sum(axis=1).astype(float)


def end_labels(ax, x_end: float, ends: Sequence[float], texts: Sequence[str],
               colours: Sequence, *, dx_points: float = 14.0, fontsize: float = 8.0,
               gid: str = "label") -> list:
    """Labels of curves ending at (`x_end`, `ends`) [data], `dx_points` to the right of the
    ends, with leader lines; made before the layout is settled (so that it makes room for
    them) and stacked after it by :func:`stack_labels`.  Returns the annotations."""
    return [ax.annotate(text, xy=(x_end, y), xycoords="data", xytext=(dx_points, 0.0),
                        textcoords="offset points", fontsize=fontsize, color=colour,
                        va="center", ha="left", gid=gid, annotation_clip=False,
                        arrowprops=dict(arrowstyle="-", color="0.6", lw=0.6, shrinkA=0,
                                        shrinkB=0))
            for y, text, colour in zip(ends, texts, colours)]


def stack_labels(ax, anns: Sequence) -> None:
    """Move the end labels `anns` (:func:`end_labels`) vertically into a column, each as
    near its curve's end as the others allow and at least one text height (measured with
    the renderer) from the next, inside the axes' height when they fit.  The layout must be
    frozen (:func:`freeze_layout`)."""
    if not anns:
        return
    fig = ax.figure
    renderer = fig.canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    pts = fig.dpi / 72.0
    ys = [float(ax.transData.transform(a.xy)[1]) for a in anns]
    gap = max(_text_box(a, renderer).height for a in anns) + 1.5
    pos = spread_labels(ys, gap=gap, lo=frame.y0 + 0.5 * gap, hi=frame.y1 - 0.5 * gap)
    for a, y, p in zip(anns, ys, pos):
        a.xyann = (a.xyann[0], (p - y) / pts)


def label_boxes(fig, gid: str = "label") -> list:
    """Display-coordinate boxes of the texts of `fig` with ``gid`` (for checks)."""
    renderer = fig.canvas.get_renderer()
    return [_text_box(t, renderer) for ax in fig.axes for t in ax.texts
            if t.get_gid() == gid]


def _text_box(t, renderer):
    """The box of a Text's (or an Annotation's) text alone, not of its leader line."""
    from matplotlib.text import Text

    if hasattr(t, "update_positions"):          # an Annotation: place its text first
        t.update_positions(renderer)
    return Text.get_window_extent(t, renderer)


def overlapping(boxes: Sequence) -> list[tuple[int, int]]:
    """Pairs (i, j), i < j, of `boxes` that overlap (touching edges do not)."""
    return [(i, j) for i in range(len(boxes)) for j in range(i + 1, len(boxes))
            if _overlaps(boxes[i], boxes[j], -1e-6)]
