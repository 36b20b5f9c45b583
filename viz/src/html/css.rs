//! The page's style sheet.

/// Layout: the picture with its controls on the left, readouts and charts on the right
/// (below on a narrow screen); event marks on the slider's track. The picture and the charts
/// shrink to a screen narrower than they are (their drawing scales with its `viewBox`), so
/// that the page never scrolls sideways.
pub(crate) const CSS: &str = r#"
body{margin:0;font-family:system-ui,sans-serif;color:#1c2833;background:#f7f8fa}
.kl{max-width:1280px;margin:0 auto;padding:12px 18px}
.kl h1{font-size:1.25rem;font-weight:600;margin:4px 0 10px}
.kl-row{display:flex;flex-wrap:wrap;gap:18px;align-items:flex-start}
.kl-figure{margin:0;background:white;border:1px solid #d5dbe1;border-radius:6px;padding:8px}
.kl-figure>svg{display:block;max-width:100%;height:auto}
.kl-controls{display:flex;align-items:center;gap:10px;margin-top:8px}
.kl-controls button{min-width:5em;padding:4px 10px;font:inherit;border:1px solid #8a99a8;border-radius:4px;background:#eef2f6;cursor:pointer}
.kl-track{position:relative;flex:1;min-width:160px}
.kl-track input{width:100%;margin:0;display:block}
.kl-marks{position:absolute;left:0;right:0;top:-5px;bottom:-5px;pointer-events:none}
.kl-mark{position:absolute;top:0;bottom:0;width:5px;margin-left:-2.5px;background:#c0143c;border-radius:1px;pointer-events:auto;cursor:pointer}
.kl-events li{cursor:pointer}
.kl-mark.kl-singular-crossing{background:#7570b3}
.kl-events{list-style:none;margin:6px 0 0;padding:0;font-size:.85rem;color:#c0143c}
.kl-key{display:inline-block;width:3px;height:.9em;margin-right:6px;vertical-align:middle;background:#c0143c}
.kl-key.kl-singular-crossing{background:#7570b3}
.kl-side{display:flex;flex-direction:column;gap:8px}
.kl-readouts{border-collapse:collapse;background:white;border:1px solid #d5dbe1;font-variant-numeric:tabular-nums}
.kl-readouts th{text-align:left;font-weight:500;padding:3px 10px}
.kl-readouts td{padding:3px 6px}
.kl-value{text-align:right;min-width:6em;font-family:ui-monospace,monospace}
.kl-unit{color:#5d6d7e}
.kl-charts{display:flex;flex-direction:column;gap:6px}
.kl-chart{max-width:100%;height:auto;background:white;border:1px solid #d5dbe1;border-radius:4px}
.kl-note{font-size:.8rem;color:#5d6d7e}
.kl-sliders{flex:1;display:flex;flex-direction:column;gap:4px;min-width:200px}
.kl-axis{display:flex;align-items:center;gap:8px;font-size:.9rem}
.kl-axis span{min-width:4em}
.kl-axis input{flex:1}
#kl-mechanism.kl-unreachable>:not(.kl-pivot){visibility:hidden}
.kl-status{margin:6px 0 0;min-height:1.2em;font-weight:600;color:#c0143c}
.kl-drawing-note{margin:6px 0 0;font-size:.85rem;color:#a0522d;max-width:640px}
"#;
