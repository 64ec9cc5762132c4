#!/usr/bin/env node
// Opens a page of ashlar's HTML viewer in Debian's chromium (headless,
// WebGL through SwiftShader) and checks what a user would see.
// Usage: node check_viewer.js ASHLAR OUT arch|dome|animation|mechanism|network
//   ASHLAR  the ashlar program, which writes the page (viewer_pages.lua)
//   OUT     a folder for the page and the screenshots
// Every case checks that the page loads without console errors and draws
// something; then
//   arch: a planar arch opens in the front view, orthographic, spanning
//         most of the width; the key names each colour drawn and the scale
//         bar reads the arrows as a round force; the view buttons and the
//         orthographic box change the camera and the picture; the forces
//         and thrust line show in their colours and go when switched off,
//         hovering or tapping the crown names its voussoir, hovering an
//         arrow shows its interface's forces;
//   dome: blocks coloured by height with coolwarm are red at the top and
//         blue at the bottom, and the legend shows the map and its label,
//         from 0;
//   animation: a simulation's page has a player (the still pages have
//         none) and plays as it opens; the red block it drops is lower on
//         the screen at the last frame than at the first, and hovering it
//         there names it; playing moves the time on, pausing stops it;
//   mechanism: a load factor's page plays its mechanism: it has a player,
//         opens paused at the extreme and says how far the fastest centroid
//         moved; the red (fastest) block lies where the load factor's
//         mechanism puts it: from the rest frame to the extreme its middle
//         moves on the screen by the mechanism's displacement (Lua's own,
//         mechanism.json) at the page's scale; the key, the force-free page
//         and the hinges (the limit layer, which switches off);
//   network: a dome's thrust network and the forces at the contact
//         vertices: orange tubes, blue normal and magenta friction arrows,
//         a key naming compression, friction and the thrust network, the
//         scale bar; the network goes when switched off.
// Exits 77 (ctest: skipped) when chromium is not installed, 2 when
// puppeteer-core is not (npm ci in this folder), 1 when a check fails.
'use strict';

const { execFileSync } = require('child_process');
const fs = require('fs');
const path = require('path');

const CHROMIUM = process.env.ASHLAR_CHROMIUM || '/usr/bin/chromium';
const WIDTH = 800, HEIGHT = 600;

const [ashlar, out, name] = process.argv.slice(2);
const CASES = ['arch', 'dome', 'animation', 'mechanism', 'network'];
if (!ashlar || !out || !CASES.includes(name)) {
  console.error(`usage: node check_viewer.js ASHLAR OUT ${CASES.join('|')}`);
  process.exit(1);
}
if (!fs.existsSync(CHROMIUM)) {
  console.log(`SKIPPED: ${CHROMIUM} is not installed (Debian: apt-get install chromium; ./run.sh build does it)`);
  process.exit(77);
}
let puppeteer;
try {
  puppeteer = require('puppeteer-core');
} catch (e) {
  console.error(`puppeteer-core is not installed: run \`npm ci\` in ${__dirname} once ` +
                '(./run.sh build does it; tests never download at test time).');
  process.exit(2);
}

let failures = 0;
function check(ok, what) {
  console.log(`${ok ? 'ok' : 'not ok'} - ${what}`);
  if (!ok) failures += 1;
}

// Pixel statistics of a PNG screenshot, decoded by the browser itself,
// within `region` ([x0, y0, x1, y1], default all) and outside the viewer's
// panels. Classes: background, saturated blue (hue 190-250), orange
// (20-50), red (<= 12 or >= 348), magenta (320-345), and everything else
// drawn.
async function analyse(browser, shot, region) {
  const page = await browser.newPage();
  try {
    return await page.evaluate(async (base64, panels, region) => {
      const image = new Image();
      image.src = 'data:image/png;base64,' + base64;
      await image.decode();
      const canvas = document.createElement('canvas');
      canvas.width = image.width;
      canvas.height = image.height;
      const context = canvas.getContext('2d');
      context.drawImage(image, 0, 0);
      const { data } = context.getImageData(0, 0, image.width, image.height);
      const [x0, y0, x1, y1] = region || [0, 0, image.width, image.height];
      const counts = { drawn: 0, blue: 0, orange: 0, red: 0, magenta: 0, total: 0 };
      const drawn_rows = [];
      const blue_points = [];
      let warmth = 0, top = image.height, bottom = -1, left = image.width, right = -1;
      const red_box = [image.width, image.height, -1, -1];
      const in_panel = (x, y) => panels.some((p) => x >= p[0] && x < p[2] && y >= p[1] && y < p[3]);
      for (let y = y0; y < y1; ++y) {
        for (let x = x0; x < x1; ++x) {
          if (in_panel(x, y)) continue;
          const k = 4 * (y * image.width + x);
          const r = data[k] / 255, g = data[k + 1] / 255, b = data[k + 2] / 255;
          counts.total += 1;
          // The page's background is (0.957, 0.957, 0.945).
          if (Math.abs(r - 0.957) < 0.03 && Math.abs(g - 0.957) < 0.03 && Math.abs(b - 0.945) < 0.03) continue;
          counts.drawn += 1;
          top = Math.min(top, y); bottom = Math.max(bottom, y);
          left = Math.min(left, x); right = Math.max(right, x);
          warmth += r - b;
          const max = Math.max(r, g, b), min = Math.min(r, g, b);
          const saturation = max > 0 ? (max - min) / max : 0;
          if (saturation < 0.45 || max < 0.25) continue;
          let hue;
          if (max === r) hue = (60 * (g - b) / (max - min) + 360) % 360;
          else if (max === g) hue = 60 * (b - r) / (max - min) + 120;
          else hue = 60 * (r - g) / (max - min) + 240;
          if (hue >= 190 && hue <= 250) { counts.blue += 1; blue_points.push([x, y]); }
          else if (hue >= 20 && hue <= 50) counts.orange += 1;
          else if (hue >= 320 && hue <= 345) counts.magenta += 1;
          else if (hue <= 12 || hue >= 348) {
            counts.red += 1;
            red_box[0] = Math.min(red_box[0], x); red_box[1] = Math.min(red_box[1], y);
            red_box[2] = Math.max(red_box[2], x); red_box[3] = Math.max(red_box[3], y);
          }
        }
      }
      return { ...counts, warmth: counts.drawn ? warmth / counts.drawn : 0,
               box: [left, top, right, bottom], red_box, blue_points };
    }, shot.png, shot.panels, region);
  } finally {
    await page.close();
  }
}

async function screenshot(page, file) {
  // Two frames: the viewer draws on the next animation frame after a change.
  await page.evaluate(() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))));
  const png = await page.screenshot({ encoding: 'base64' });
  fs.writeFileSync(path.join(out, file), Buffer.from(png, 'base64'));
  const panels = await page.$$eval('.panel', (elements) => elements.map((element) => {
    const r = element.getBoundingClientRect();
    return [Math.floor(r.left), Math.floor(r.top), Math.ceil(r.right), Math.ceil(r.bottom)];
  }));
  return { png, panels };
}

async function info_after_hover(page, x, y) {
  await page.mouse.move(x, y);
  await page.evaluate(() => new Promise((done) => requestAnimationFrame(done)));
  return page.$eval('#info', (element) => element.innerText);
}

// What the page's camera does: the view chosen and its projection.
async function camera_state(page) {
  return page.evaluate(() => ({ view: document.body.dataset.view, projection: document.body.dataset.projection }));
}

// The share of pixels that differ between two screenshots.
async function difference(browser, a, b) {
  const page = await browser.newPage();
  try {
    return await page.evaluate(async (a, b) => {
      const pixels = async (base64) => {
        const image = new Image();
        image.src = 'data:image/png;base64,' + base64;
        await image.decode();
        const canvas = document.createElement('canvas');
        canvas.width = image.width;
        canvas.height = image.height;
        const context = canvas.getContext('2d');
        context.drawImage(image, 0, 0);
        return context.getImageData(0, 0, image.width, image.height).data;
      };
      const [p, q] = [await pixels(a), await pixels(b)];
      let differ = 0;
      for (let k = 0; k < p.length; k += 4) {
        if (Math.abs(p[k] - q[k]) + Math.abs(p[k + 1] - q[k + 1]) + Math.abs(p[k + 2] - q[k + 2]) > 30) differ += 1;
      }
      return differ / (p.length / 4);
    }, a.png, b.png);
  } finally {
    await page.close();
  }
}

async function check_views(browser, page, front) {
  // The page's scene: the arrows' scale it drew with.
  const scene = await page.evaluate(() => JSON.parse(document.getElementById('ashlar-scene').textContent));
  const newtons_per_metre = 1 / scene.force_scale;
  const mantissa = newtons_per_metre / Math.pow(10, Math.floor(Math.log10(newtons_per_metre) + 1e-9));
  check([1, 2, 5].some((m) => Math.abs(mantissa - m) < 1e-6),
        `the automatic arrow scale is a round number: ${newtons_per_metre} N per m`);
  const panels = await page.evaluate(() => ({
    key: document.getElementById('key').innerText,
    key_shown: getComputedStyle(document.getElementById('key')).display !== 'none',
    scale: document.getElementById('scale').innerText,
    rule: document.getElementById('scale-rule').getBoundingClientRect().width,
  }));
  check(panels.key_shown && ['compression', 'tension', 'contact interfaces', 'thrust line'].every((l) => panels.key.includes(l)),
        `the key names every colour drawn: ${JSON.stringify(panels.key)}`);
  const unit = newtons_per_metre >= 1e6 ? [1e6, 'MN'] : newtons_per_metre >= 1e3 ? [1e3, 'kN'] : [1, 'N'];
  const note = `1 m of arrow = ${Number((newtons_per_metre / unit[0]).toPrecision(4))} ${unit[1]}`;
  check(panels.scale.includes(note), `the scale bar says ${JSON.stringify(note)}: ${JSON.stringify(panels.scale)}`);
  check(/force scale\s+[125]0* (N|kN|MN)\b/.test(panels.scale) && panels.rule >= 40 && panels.rule <= 126,
        `it shows a round force, ${panels.rule.toFixed(0)} px long`);

  const opening = await camera_state(page);
  check(opening.view === 'front' && opening.projection === 'orthographic',
        `a planar arch opens in the front view, orthographic: ${JSON.stringify(opening)}`);
  const [left, , right] = front.box;
  check(right - left > 0.7 * WIDTH, `and spans most of the width: ${right - left} of ${WIDTH} px`);

  await page.click('#views button[data-view="top"]');
  const top = await screenshot(page, 'arch_top.png');
  const top_state = await camera_state(page);
  const top_drawn = await analyse(browser, top);
  const front_height = front.box[3] - front.box[1], top_height = top_drawn.box[3] - top_drawn.box[1];
  check(top_state.view === 'top' && top_height < 0.6 * front_height,
        `the top button looks down: ${JSON.stringify(top_state)}, the arch ${top_height} px deep against ${front_height} px high`);
  await page.click('#views button[data-view="side"]');
  const side = await screenshot(page, 'arch_side.png');
  const side_drawn = await analyse(browser, side);
  check((await camera_state(page)).view === 'side' && side_drawn.box[2] - side_drawn.box[0] < 0.6 * (right - left),
        `the side button looks along the span: ${side_drawn.box[2] - side_drawn.box[0]} px wide`);
  await page.click('#views button[data-view="iso"]');
  const iso_ortho = await screenshot(page, 'arch_iso_orthographic.png');
  await page.click('#orthographic');
  const iso = await screenshot(page, 'arch_iso.png');
  const iso_state = await camera_state(page);
  const changed = await difference(browser, iso_ortho, iso);
  check(iso_state.view === 'iso' && iso_state.projection === 'perspective' && changed > 0.005,
        `the orthographic box switches to perspective: ${JSON.stringify(iso_state)}, ${(100 * changed).toFixed(1)} % of pixels change`);
  await page.click('#orthographic');
  await page.click('#views button[data-view="front"]');
  const back = await camera_state(page);
  check(back.view === 'front' && back.projection === 'orthographic', `and back: ${JSON.stringify(back)}`);
}

async function check_arch(browser, page) {
  const drawn = await analyse(browser, await screenshot(page, 'arch.png'));
  await check_views(browser, page, drawn);
  check(drawn.drawn > 0.03 * drawn.total, `the arch covers ${(100 * drawn.drawn / drawn.total).toFixed(1)} % of the canvas`);
  check(drawn.blue > 200, `force arrows show in the compression colour (${drawn.blue} blue pixels)`);
  check(drawn.orange > 100, `the thrust line shows in orange (${drawn.orange} pixels)`);

  await page.click('#layer-forces');
  const no_forces = await analyse(browser, await screenshot(page, 'arch_no_forces.png'));
  check(no_forces.blue < drawn.blue / 20, `switching forces off removes the arrows (${no_forces.blue} blue pixels left)`);
  check(no_forces.orange > 100, 'the thrust line stays');
  await page.click('#layer-thrust');
  const bare = await analyse(browser, await screenshot(page, 'arch_bare.png'));
  check(bare.orange < drawn.orange / 20, `switching the thrust line off removes it (${bare.orange} orange pixels left)`);

  // The crown: just under the highest drawn pixel, in the middle of the
  // arch's width. Nine voussoirs: the fifth is the keystone.
  const [left, top, right, bottom] = bare.box;
  const crown = await info_after_hover(page, Math.round((left + right) / 2), top + Math.round(0.04 * (bottom - top)));
  check(/^voussoir 5\b/.test(crown), `hovering the crown names it: ${JSON.stringify(crown.split('\n')[0])}`);
  check(/mass\s+\d/.test(crown), 'and gives its mass');
  // A tap (no hover on touch screens) picks too.
  await info_after_hover(page, 2, HEIGHT / 2);
  await page.touchscreen.tap(Math.round((left + right) / 2), top + Math.round(0.04 * (bottom - top)));
  await page.evaluate(() => new Promise((done) => requestAnimationFrame(done)));
  const tapped = await page.$eval('#info', (element) => element.innerText);
  check(/^voussoir 5\b/.test(tapped), `tapping the crown names it: ${JSON.stringify(tapped.split('\n')[0])}`);

  // An arrow: the blue pixel with the most blue neighbours.
  await page.click('#layer-forces');
  const forces = await analyse(browser, await screenshot(page, 'arch_forces.png'));
  const blue = new Set(forces.blue_points.map(([x, y]) => `${x},${y}`));
  let best = null, best_count = -1;
  for (const [x, y] of forces.blue_points) {
    let count = 0;
    for (let dy = -3; dy <= 3; ++dy) for (let dx = -3; dx <= 3; ++dx) count += blue.has(`${x + dx},${y + dy}`);
    if (count > best_count) { best = [x, y]; best_count = count; }
  }
  check(best !== null, 'an arrow to hover');
  if (best) {
    const arrow = await info_after_hover(page, best[0], best[1]);
    check(/^force \d+-\d+/.test(arrow), `hovering an arrow names its interface: ${JSON.stringify(arrow.split('\n')[0])}`);
    check(/normal force\s+[\d.]+ kN \(compression\)/.test(arrow), 'and gives its normal force');
  }
}

async function check_dome(browser, page) {
  const shot = await screenshot(page, 'dome.png');
  const all = await analyse(browser, shot);
  check(all.drawn > 0.05 * all.total, `the dome covers ${(100 * all.drawn / all.total).toFixed(1)} % of the canvas`);
  // Thirds of the dome's picture, top and bottom.
  const [left, top, right, bottom] = all.box;
  const third = Math.round((bottom - top) / 3);
  const upper = await analyse(browser, shot, [left, top, right + 1, top + third]);
  const lower = await analyse(browser, shot, [left, bottom - third, right + 1, bottom + 1]);
  check(upper.red > 10 * upper.blue && upper.red > 0.2 * upper.drawn,
        `the top (highest values) is red: ${upper.red} red, ${upper.blue} blue of ${upper.drawn} pixels`);
  check(lower.blue > 10 * lower.red && lower.blue > 0.2 * lower.drawn,
        `the bottom (lowest values) is blue: ${lower.blue} blue, ${lower.red} red of ${lower.drawn} pixels`);
  const legend = await page.$eval('#legend', (element) => ({
    shown: getComputedStyle(element).display !== 'none',
    text: element.innerText,
    bar: getComputedStyle(element.querySelector('.bar')).backgroundImage,
  }));
  check(legend.shown && legend.text.includes('height (m)'), `the legend shows its label: ${JSON.stringify(legend.text)}`);
  const lo = await page.$eval('#legend-lo', (element) => element.textContent);
  check(lo === '0', `the legend of heights (none negative) starts at 0: ${JSON.stringify(lo)}`);
  const stops = [...legend.bar.matchAll(/rgb\((\d+), (\d+), (\d+)\)/g)].map((m) => m.slice(1).map(Number));
  const [first, last] = [stops[0], stops[stops.length - 1]];
  check(stops.length > 10 && first[2] > first[0] + 80 && last[0] > last[2] + 80,
        `the legend runs from blue to red: ${JSON.stringify(first)} to ${JSON.stringify(last)}`);
}

async function player_time(page) {
  return page.$eval('#time', (slider) => Number(slider.value));
}

async function check_animation(browser, page) {
  // It plays as it opens; pausing and the slider bring it back to t = 0.
  await new Promise((done) => setTimeout(done, 300));
  const opened = await page.$eval('#play', (element) => element.textContent);
  const played = await player_time(page);
  check(opened === 'pause' && played > 0, `the page plays as it opens: ${played} s after 0.3 s, button ${opened}`);
  await page.click('#play');
  await page.$eval('#time', (slider) => {
    slider.value = slider.min;
    slider.dispatchEvent(new Event('input'));
  });
  const player = await page.$eval('#player', (element) => ({
    shown: getComputedStyle(element).display !== 'none',
    button: element.querySelector('#play').textContent,
    min: Number(element.querySelector('#time').min),
    max: Number(element.querySelector('#time').max),
    text: element.querySelector('#time-text').textContent,
  }));
  check(player.shown && player.button === 'play', `the player shows, paused: ${JSON.stringify(player)}`);
  check(player.min === 0 && Math.abs(player.max - 0.8) < 1e-6 && player.text === '0.000 s / 0.800 s',
        `its slider runs over the simulated time, 0 to 0.8 s: ${player.text}`);

  const first = await analyse(browser, await screenshot(page, 'animation_first.png'));
  check(first.red > 500, `the red block shows at t = 0 (${first.red} pixels)`);
  await page.$eval('#time', (slider) => {
    slider.value = slider.max;
    slider.dispatchEvent(new Event('input'));
  });
  const last = await analyse(browser, await screenshot(page, 'animation_last.png'));
  const middle = (box) => [(box[0] + box[2]) / 2, (box[1] + box[3]) / 2];
  const [, y0] = middle(first.red_box), [x1, y1] = middle(last.red_box);
  check(last.red > 500 && y1 - y0 > 50,
        `at the last frame the block has fallen: its middle from y = ${y0} to ${y1} px (${last.red} pixels)`);
  const hovered = await info_after_hover(page, Math.round(x1), Math.round(y1));
  check(/^block 2\b/.test(hovered), `hovering it where it landed names it: ${JSON.stringify(hovered.split('\n')[0])}`);

  // Play (from the start, since the time is at the end), then pause.
  await page.click('#play');
  await new Promise((done) => setTimeout(done, 300));
  const playing = await player_time(page);
  check(playing > 0 && playing < 0.8, `playing moves the time on: ${playing} s after 0.3 s`);
  await page.click('#play');
  const paused = await player_time(page);
  await new Promise((done) => setTimeout(done, 300));
  const later = await player_time(page);
  const button = await page.$eval('#play', (element) => element.textContent);
  check(later === paused && button === 'play', `pausing stops it: ${paused} s, 0.3 s later ${later} s`);
}

async function set_slider(page, value) {
  await page.$eval('#time', (slider, value) => {
    slider.value = value;
    slider.dispatchEvent(new Event('input'));
  }, value);
}

async function check_mechanism(browser, page) {
  const expected = JSON.parse(fs.readFileSync(path.join(out, 'mechanism.json'), 'utf8'));
  const player = await page.$eval('#player', (element) => ({
    shown: getComputedStyle(element).display !== 'none',
    button: element.querySelector('#play').textContent,
    value: Number(element.querySelector('#time').value),
    text: element.querySelector('#time-text').textContent,
  }));
  check(player.shown && player.button === 'play' && player.value === 1,
        `a load factor's page has a player, paused at the mechanism's extreme: ${JSON.stringify(player)}`);
  check(player.text === 'mechanism 0.2 m / 0.2 m', `it states the scale: ${player.text}`);
  const summary = await page.$eval('#summary', (element) => element.textContent);
  check(summary.includes("the fastest block's centroid moved 0.2 m at its extreme"), `so does the summary: ${summary}`);

  const moved = await analyse(browser, await screenshot(page, 'mechanism_extreme.png'));
  await set_slider(page, 0);
  const rest_shot = await screenshot(page, 'mechanism_rest.png');
  const rest = await analyse(browser, rest_shot);
  check(rest.red > 100 && moved.red > 100, `the fastest block is red at rest and at the extreme (${rest.red}, ${moved.red} pixels)`);
  // The page's scale from the rest frame: the arch's width on the screen over its width in metres.
  const pixels_per_metre = (rest.box[2] - rest.box[0]) / expected.width;
  const middle = (box) => [(box[0] + box[2]) / 2, (box[1] + box[3]) / 2];
  const [x0, y0] = middle(rest.red_box), [x1, y1] = middle(moved.red_box);
  const want = [expected.shift[0] * pixels_per_metre, -expected.shift[1] * pixels_per_metre];  // screen y runs down
  const got = [x1 - x0, y1 - y0];
  const miss = Math.hypot(got[0] - want[0], got[1] - want[1]);
  check(Math.hypot(...want) > 20 && miss < 0.15 * Math.hypot(...want) + 4,
        `the extreme moves block ${expected.block} by the mechanism's displacement: ${got.map((v) => v.toFixed(1))} px, ` +
        `expected ${want.map((v) => v.toFixed(1))} px (${pixels_per_metre.toFixed(1)} px/m), off by ${miss.toFixed(1)} px`);
  await set_slider(page, 2);
  const back = await analyse(browser, await screenshot(page, 'mechanism_back.png'));
  check(Math.abs(middle(back.red_box)[0] - x0) <= 1 && Math.abs(middle(back.red_box)[1] - y0) <= 1,
        'and back at rest at the end of the loop');

  await set_slider(page, 0);
  const limit_box = await page.$('#layer-limit');
  check(limit_box !== null, 'the hinges have their layer');
  if (limit_box) {
    await limit_box.click();
    const without = await screenshot(page, 'mechanism_no_hinges.png');
    const changed = await difference(browser, rest_shot, without) * WIDTH * HEIGHT;
    check(changed > 20, `switching the hinges off removes them (${changed.toFixed(0)} pixels change)`);
  }
  const key = await page.$eval('#key', (element) => element.innerText);
  check(key.includes('thrust line'), `the key names the thrust line at the factor: ${JSON.stringify(key)}`);
}

async function check_network(browser, page) {
  const shot = await screenshot(page, 'network.png');
  const drawn = await analyse(browser, shot);
  const panels = await page.evaluate(() => ({
    key: document.getElementById('key').innerText,
    scale: getComputedStyle(document.getElementById('scale')).display !== 'none',
  }));
  check(['compression', 'tension', 'friction', 'thrust network (thickness: force)'].every((l) => panels.key.includes(l)),
        `the key names compression, tension, friction and the network: ${JSON.stringify(panels.key)}`);
  check(panels.scale, 'the scale bar shows');
  check(drawn.orange > 300, `the thrust network shows in orange (${drawn.orange} pixels)`);
  check(drawn.blue > 100, `normal forces at the vertices in blue (${drawn.blue} pixels)`);
  check(drawn.magenta > 30, `friction at the vertices in magenta (${drawn.magenta} pixels)`);
  await page.click('#layer-thrust');
  const bare = await analyse(browser, await screenshot(page, 'network_off.png'));
  check(bare.orange < drawn.orange / 10, `switching the thrust off removes the network (${bare.orange} orange pixels left)`);
}

(async () => {
  fs.rmSync(out, { recursive: true, force: true });
  fs.mkdirSync(out, { recursive: true });
  execFileSync(ashlar, [path.join(__dirname, 'viewer_pages.lua'), name, out], { stdio: 'inherit' });
  const file = path.join(out, `${name}.html`);

  const browser = await puppeteer.launch({
    executablePath: CHROMIUM,
    headless: true,
    // Containers have no user namespaces for the sandbox and no GPU:
    // WebGL runs on SwiftShader, the CPU renderer chromium ships.
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-gpu-sandbox',
           '--no-first-run', '--no-default-browser-check', '--disable-dev-shm-usage'],
    defaultViewport: { width: WIDTH, height: HEIGHT, deviceScaleFactor: 1 },
  });
  try {
    const page = await browser.newPage();
    const errors = [];
    page.on('console', (message) => { if (message.type() === 'error') errors.push(message.text()); });
    page.on('pageerror', (error) => errors.push(error.message));
    page.on('requestfailed', (request) => errors.push(`request failed: ${request.url()}`));
    await page.goto('file://' + path.resolve(file), { waitUntil: 'load' });
    await page.waitForSelector('#view canvas', { timeout: 15000 });
    const html = fs.readFileSync(file, 'utf8');
    check(!/<script[^>]+src=|<link[^>]+href=/.test(html), 'the page loads no other file');
    if (name === 'animation') {
      await check_animation(browser, page);
    } else if (name === 'mechanism') {
      await check_mechanism(browser, page);
    } else {
      const player = await page.$eval('#player', (element) => getComputedStyle(element).display);
      check(player === 'none', 'a still has no player');
      if (name === 'arch') await check_arch(browser, page);
      else if (name === 'network') await check_network(browser, page);
      else await check_dome(browser, page);
    }
    check(errors.length === 0, `no console errors${errors.length ? ': ' + errors.join(' | ') : ''}`);
  } finally {
    await browser.close();
  }
  console.log(failures === 0 ? `${name}: all checks passed (screenshots in ${out})` : `${name}: ${failures} checks failed`);
  process.exit(failures === 0 ? 0 : 1);
})().catch((error) => {
  console.error(error);
  process.exit(1);
});
