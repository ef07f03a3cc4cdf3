"""The report's frame slider: an animation's frames (PNG pages of the rendered soil with the
contact pressure and the gap under the footing) stacked in one ``<figure>``, one shown at a
time, with an ``<input type=range>`` to pick it.

:data:`SCRIPT` is the report's only script, inline, a few lines with no external reference:
it shows the frame the slider points at and writes that frame's label next to it. Without it
(scripts off) the page shows the last frame and the slider does nothing; printed, the page
shows the frame the slider was left at, without the slider.
"""

from __future__ import annotations

import html

from ..framework.figure_record import FigureRecord
from .images import data_uri

__all__ = ["SCRIPT", "animation_html"]

#: The report's one inline script: each slider shows its frame and that frame's label.
SCRIPT = """<script>
for (const fig of document.querySelectorAll("figure.anim")) {
  const frames = fig.querySelectorAll("img"), slider = fig.querySelector("input");
  const label = fig.querySelector("output");
  const show = () => {
    frames.forEach((img, k) => { img.hidden = k !== Number(slider.value); });
    label.textContent = frames[Number(slider.value)].dataset.label;
  };
  slider.addEventListener("input", show);
  show();
}
</script>"""


def animation_html(record: FigureRecord, caption: str) -> str:
    """The ``<figure class="anim">`` of ``record``'s frames (the last one shown first)."""

    frames = [(p, label) for p, label in record.frames if p.is_file()]
    if not frames:
        return (f'<p class="notice">Animation “{html.escape(record.caption.title)}”: its frames'
                " are missing.</p>")
    last = len(frames) - 1
    images = "".join(
        f'<img class="render" alt="{html.escape(label)}" data-label="{html.escape(label)}" '
        f'src="{data_uri(path)}"{"" if k == last else " hidden"}>'
        for k, (path, label) in enumerate(frames))
    return (f'<figure class="anim"><div class="frames">{images}</div>'
            f'<div class="slider"><label>frame <input type="range" min="0" max="{last}" '
            f'step="1" value="{last}" aria-label="frame"></label> '
            f"<output>{html.escape(frames[last][1])}</output></div>{caption}</figure>")
