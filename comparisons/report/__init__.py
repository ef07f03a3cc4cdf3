"""One self-contained HTML report of every study (:mod:`.build`): its page (:mod:`.html`),
the studies' Markdown as HTML (:mod:`.markdown`), figures (:mod:`.figures`,
:mod:`.animation`, :mod:`.images`) and printing to PDF (:mod:`.printing`)."""
