//! The page's script: shows frame `i` of the precomputed motion (moves every item, the
//! traced points' dots, the readouts and the charts' cursors), plays and pauses, follows the
//! slider, and jumps to an event when its mark is clicked.
//!
//! The page's address can ask for a pose: `page.html#i=40` shows frame 40 and does not play;
//! `page.html#probe=0,40,80` moves the slider to each frame in turn, as a user would, and
//! writes what is then drawn (every joint and traced dot, the readouts' texts, the charts'
//! cursors) as lines into a `<pre id="kl-probe">`, read back by the browser test.

/// The script (plain ES5, no library).
pub(crate) const SCRIPT: &str = r#"
(function () {
  'use strict';
  var D = JSON.parse(document.getElementById('kl-data').textContent);
  var svg = document.getElementById('kl-drawing');
  var slider = document.getElementById('kl-slider');
  var button = document.getElementById('kl-play');
  var n = D.frames.length;
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
    values.forEach(function (el, k) { el.textContent = D.ch[k].v[i].toFixed(D.ch[k].dec); });
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
    slider.value = String(i);
    if (row) {
      slider.setAttribute('aria-valuetext', row.cells[0].textContent + ' = ' + row.cells[1].textContent + ' ' + row.cells[2].textContent);
    }
    current = i;
  }

  var playing = false, start = 0, from = 0;
  function position(u) {
    if (D.bf) { var c = u % 2; return c <= 1 ? c : 2 - c; }
    return u % 1;
  }
  function tick(now) {
    if (!playing) { return; }
    var i = Math.round(position((now - start) / (1000 * D.seconds) + from) * (n - 1));
    if (i !== current) { show(i); }
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
  slider.addEventListener('input', function () { pause(); show(parseInt(slider.value, 10)); });
  // A click on an event's mark (or its line in the list) shows the mechanism there.
  all(document, '[data-at]').forEach(function (el) {
    el.addEventListener('click', function () { pause(); show(Math.min(parseInt(el.getAttribute('data-at'), 10), n - 1)); });
  });

  function probe(i) {
    slider.value = String(i);
    slider.dispatchEvent(new Event('input'));
    var at = +slider.value, lines = [];
    all(svg, 'circle.kl-joint').forEach(function (c) {
      lines.push('frame=' + at + ' joint item=' + c.getAttribute('data-item') + ' point=' + c.getAttribute('data-point') +
        ' name=' + (c.getAttribute('data-name') || '-') + ' x=' + c.getAttribute('cx') + ' y=' + c.getAttribute('cy'));
    });
    dots.forEach(function (c) {
      lines.push('frame=' + at + ' dot trace=' + c.getAttribute('data-trace') + ' name=' + (c.getAttribute('data-name') || '-') +
        ' x=' + c.getAttribute('cx') + ' y=' + c.getAttribute('cy'));
    });
    values.forEach(function (el, k) { lines.push('frame=' + at + ' value ch=' + k + ' text=' + el.textContent); });
    charts.forEach(function (c, k) {
      lines.push('frame=' + at + ' cursor chart=' + k + ' x=' + c.line.getAttribute('x1') + ' y=' + c.dot.getAttribute('cy'));
    });
    return lines;
  }

  var hash = window.location.hash;
  var one = /^#i=(\d+)$/.exec(hash), many = /^#probe=([\d,]+)$/.exec(hash);
  if (one) {
    show(Math.min(parseInt(one[1], 10), n - 1));
  } else if (many) {
    var lines = [];
    many[1].split(',').forEach(function (s) {
      if (s !== '') { lines = lines.concat(probe(Math.min(parseInt(s, 10), n - 1))); }
    });
    var pre = document.createElement('pre');
    pre.id = 'kl-probe';
    pre.textContent = lines.join('\n');
    document.body.appendChild(pre);
  } else {
    show(0);
    if (D.autoplay) { play(); }
  }
})();
"#;
