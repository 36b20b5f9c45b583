//! The page's script: shows frame `i` of the precomputed motion (moves every item, the
//! traced points' dots, the readouts and the charts' cursors), plays and pauses, follows the
//! slider, and jumps to an event when its mark is clicked.
//!
//! The readouts are written by the rule of [`Format`](crate::plot::digits::Format), repeated
//! here (`format`): from the page's numbers, which are the readouts' texts as Rust wrote
//! them, the same texts again.
//!
//! The page's address can ask for a pose: `page.html#i=40` shows frame 40 and does not play;
//! `page.html#probe=0,40,80` moves the slider to each frame in turn, as a user would, and
//! writes what is then drawn (every joint and traced dot, the readouts' texts, the charts'
//! cursors) as lines into a `<pre id="kl-probe">`, read back by the browser test.
//!
//! A grid's page (several inputs, [`html_grid`](super::html_grid)) has one slider per input:
//! the cell under the sliders is shown, or, where the grid could not be assembled, the
//! mechanism is hidden, the other readouts show a dash and the status line says so. Its
//! address takes cells as indices along each input: `page.html#cell=3:5`, and
//! `page.html#probe=3:5,10:2` (each written as frame = the cell's number, with a line saying
//! whether it is reachable). Play moves the first input along its row.

/// The script (plain ES5, no library).
pub(crate) const SCRIPT: &str = r#"
(function () {
  'use strict';
  var D = JSON.parse(document.getElementById('kl-data').textContent);
  var svg = document.getElementById('kl-drawing');
  var G = D.grid || null;
  var sliders = G ? Array.prototype.slice.call(document.querySelectorAll('input.kl-slider')) : [document.getElementById('kl-slider')];
  var slider = sliders[0];
  var button = document.getElementById('kl-play');
  var mech = document.getElementById('kl-mechanism');
  var status = document.getElementById('kl-status');
  // Played along: the frames of a sweep, or the first input's values on a grid.
  var n = G ? G.n[0] : D.frames.length;
  // On a grid, the first `ni` readouts are the inputs, read from the sliders.
  var ni = G ? G.n.length : 0;
  var all = function (root, sel) { return Array.prototype.slice.call(root.querySelectorAll(sel)); };
  // Coordinates are held in tenths of a pixel, angles in tenths of a degree.
  var t = function (v) { return String(v / 10); };
  var items = D.items.map(function (it, k) {
    return {
      it: it,
      el: svg.querySelector('.kl-shape[data-item="' + k + '"]'),
      joints: all(svg, 'circle.kl-joint[data-item="' + k + '"]')
    };
  });
  var dots = all(svg, 'circle.kl-dot');
  var values = D.ch.map(function (c, k) { return document.getElementById('kl-v' + k); });
  var charts = D.charts.map(function (c, k) {
    var el = document.querySelector('svg.kl-chart[data-chart="' + k + '"]');
    return { c: c, line: el.querySelector('.kl-cursor'), dot: el.querySelector('.kl-cursor-dot') };
  });
  var current = 0;
  // Value `v` of readout `c` as the page's Rust writes it (`plot::digits::Format`): `v` is
  // a whole multiple of 10^c.last (the page holds the readouts' texts), written with decimals
  // down to 10^c.last, or, when c.sci, as its own digits down to 10^c.last in a mantissa and
  // a power of ten ('-5.661e-7', '1.5896e9', zero '0'); never a negative zero.
  function format(c, v) {
    if (!c.sci) {
      var s = v.toFixed(Math.max(0, -c.last));
      return /^-[0.]*$/.test(s) ? s.slice(1) : s;
    }
    if (v === 0) { return '0'; }
    // The power of ten of the leading digit: the shortest text of `v` has it.
    var e = parseInt(v.toExponential().split('e')[1], 10);
    return v.toExponential(Math.max(0, Math.min(100, e - c.last))).replace('e+', 'e');
  }
  // The first input's readout names the slider's value for assistive technology.
  var row = document.querySelector('tr.kl-readout[data-ch="0"]');

  function show(i) {
    var f = D.frames[i];
    items.forEach(function (s) {
      var o = s.it.o, kind = s.it.t;
      if (kind === 'link' || kind === 'joint') {
        var pts = [];
        for (var j = 0; j < s.it.n; j++) {
          var x = t(f[o + 2 * j]), y = t(f[o + 2 * j + 1]);
          pts.push(x + ',' + y);
          if (s.joints[j]) { s.joints[j].setAttribute('cx', x); s.joints[j].setAttribute('cy', y); }
        }
        if (s.el) { s.el.setAttribute('points', pts.join(' ')); }
      } else if (s.el) {
        var tr = 'translate(' + t(f[o]) + ' ' + t(f[o + 1]) + ')';
        if (kind !== 'pivot') { tr += ' rotate(' + t(f[o + 2]) + ')'; }
        s.el.setAttribute('transform', tr);
      }
    });
    dots.forEach(function (d, k) {
      var o = D.traces.o + 2 * k;
      d.setAttribute('cx', t(f[o]));
      d.setAttribute('cy', t(f[o + 1]));
    });
    values.forEach(function (el, k) { if (k >= ni) { el.textContent = format(D.ch[k], D.ch[k].v[i]); } });
    charts.forEach(function (c) {
      var xv = c.c.x < 0 ? i / Math.max(n - 1, 1) : D.ch[c.c.x].v[i];
      var m = c.c.map;
      var px = String(Math.round((m[0] + m[1] * xv) * 10) / 10);
      var py = String(Math.round((m[2] + m[3] * D.ch[c.c.y].v[i]) * 10) / 10);
      c.line.setAttribute('x1', px);
      c.line.setAttribute('x2', px);
      c.dot.setAttribute('cx', px);
      c.dot.setAttribute('cy', py);
    });
    svg.setAttribute('data-frame', String(i));
    if (G) { return; }
    slider.value = String(i);
    if (row) {
      slider.setAttribute('aria-valuetext', row.cells[0].textContent + ' = ' + row.cells[1].textContent + ' ' + row.cells[2].textContent);
    }
    current = i;
  }

  // A grid: the sliders' indices, the cell they select, and that cell shown.
  function at() { return sliders.map(function (s) { return parseInt(s.value, 10); }); }
  function cellOf(idx) {
    var c = 0;
    for (var k = idx.length - 1; k >= 0; k--) { c = c * G.n[k] + Math.max(0, Math.min(idx[k], G.n[k] - 1)); }
    return c;
  }
  function showCell(idx) {
    var c = cellOf(idx), f = G.cell[c];
    sliders.forEach(function (s, k) {
      var j = Math.max(0, Math.min(idx[k], G.n[k] - 1));
      s.value = String(j);
      values[k].textContent = format(D.ch[k], D.ch[k].v[j]);
      var r = document.querySelector('tr.kl-readout[data-ch="' + k + '"]');
      s.setAttribute('aria-valuetext', r.cells[0].textContent + ' = ' + r.cells[1].textContent + ' ' + r.cells[2].textContent);
    });
    if (f >= 0) {
      show(f);
      mech.classList.remove('kl-unreachable');
      status.textContent = '';
    } else {
      mech.classList.add('kl-unreachable');
      values.forEach(function (el, k) { if (k >= ni) { el.textContent = '\u2013'; } });
      status.textContent = 'not reached on this assembly mode';
    }
    svg.setAttribute('data-cell', String(c));
    svg.setAttribute('data-reachable', f >= 0 ? 'true' : 'false');
    current = parseInt(sliders[0].value, 10);
  }
  // Index `i` along the first input, the others where their sliders are.
  function move(i) {
    if (G) { var idx = at(); idx[0] = i; showCell(idx); } else { show(i); }
  }

  var playing = false, start = 0, from = 0;
  function position(u) {
    if (D.bf) { var c = u % 2; return c <= 1 ? c : 2 - c; }
    return u % 1;
  }
  function tick(now) {
    if (!playing) { return; }
    // A frame's time is when the browser began it, which can be before `play` read the clock
    // (a click handled within that frame, or the page's first frame): the time played is
    // never negative, so the pose stays within the frames.
    var i = Math.round(position(Math.max(0, now - start) / (1000 * D.seconds) + from) * (n - 1));
    if (i !== current) { move(i); }
    window.requestAnimationFrame(tick);
  }
  function play() {
    if (playing || n < 2) { return; }
    playing = true;
    from = current / (n - 1);
    start = window.performance.now();
    button.textContent = 'Pause';
    button.setAttribute('aria-pressed', 'true');
    window.requestAnimationFrame(tick);
  }
  function pause() {
    playing = false;
    button.textContent = 'Play';
    button.setAttribute('aria-pressed', 'false');
  }
  button.addEventListener('click', function () { if (playing) { pause(); } else { play(); } });
  sliders.forEach(function (s) {
    s.addEventListener('input', function () { pause(); if (G) { showCell(at()); } else { show(parseInt(s.value, 10)); } });
  });
  // A click on an event's mark (or its line in the list) shows the mechanism there.
  all(document, '[data-at]').forEach(function (el) {
    el.addEventListener('click', function () { pause(); show(Math.min(parseInt(el.getAttribute('data-at'), 10), n - 1)); });
  });

  function probe(text) {
    var lines = [], here;
    if (G) {
      // Each slider moved in turn, as a user does.
      text.split(':').forEach(function (v, k) {
        if (sliders[k]) { sliders[k].value = v; sliders[k].dispatchEvent(new Event('input')); }
      });
      here = +svg.getAttribute('data-cell');
      var ok = svg.getAttribute('data-reachable') === 'true';
      lines.push('frame=' + here + ' cell at=' + at().join(':') + ' reachable=' + ok);
      lines.push('frame=' + here + ' status text=' + status.textContent);
      if (!ok) {
        // What is still drawn: the frame's pivots only.
        var shown = function (sel) {
          return all(svg, sel).filter(function (el) { return window.getComputedStyle(el).visibility !== 'hidden'; }).length;
        };
        lines.push('frame=' + here + ' shown pivots=' + shown('.kl-pivot') + ' joints=' + shown('circle.kl-joint') +
          ' shapes=' + shown('.kl-shape:not(.kl-pivot)') + ' dots=' + shown('circle.kl-dot'));
        values.forEach(function (el, k) { lines.push('frame=' + here + ' value ch=' + k + ' text=' + el.textContent); });
        return lines;
      }
    } else {
      slider.value = String(Math.min(parseInt(text, 10), n - 1));
      slider.dispatchEvent(new Event('input'));
      here = +slider.value;
    }
    all(svg, 'circle.kl-joint').forEach(function (c) {
      lines.push('frame=' + here + ' joint item=' + c.getAttribute('data-item') + ' point=' + c.getAttribute('data-point') +
        ' name=' + (c.getAttribute('data-name') || '-') + ' x=' + c.getAttribute('cx') + ' y=' + c.getAttribute('cy'));
    });
    dots.forEach(function (c) {
      lines.push('frame=' + here + ' dot trace=' + c.getAttribute('data-trace') + ' name=' + (c.getAttribute('data-name') || '-') +
        ' x=' + c.getAttribute('cx') + ' y=' + c.getAttribute('cy'));
    });
    values.forEach(function (el, k) { lines.push('frame=' + here + ' value ch=' + k + ' text=' + el.textContent); });
    charts.forEach(function (c, k) {
      lines.push('frame=' + here + ' cursor chart=' + k + ' x=' + c.line.getAttribute('x1') + ' y=' + c.dot.getAttribute('cy'));
    });
    return lines;
  }

  var hash = window.location.hash;
  var one = /^#i=(\d+)$/.exec(hash), many = /^#probe=([\d,:]+)$/.exec(hash), cell = /^#cell=([\d:]+)$/.exec(hash);
  if (one && !G) {
    show(Math.min(parseInt(one[1], 10), n - 1));
  } else if (cell && G) {
    showCell(cell[1].split(':').map(function (v) { return parseInt(v, 10); }));
  } else if (many) {
    if (G) { showCell(at()); }
    var lines = [];
    many[1].split(',').forEach(function (s) {
      if (s !== '') { lines = lines.concat(probe(s)); }
    });
    var pre = document.createElement('pre');
    pre.id = 'kl-probe';
    pre.textContent = lines.join('\n');
    document.body.appendChild(pre);
  } else {
    if (G) { showCell(at()); } else { show(0); }
    if (D.autoplay) { play(); }
  }
})();
"#;
