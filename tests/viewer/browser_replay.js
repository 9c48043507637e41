// The replay page in a real browser (ctest label `browser`, docs/viewer.md): for each problem, `michi plan ... --html`
// writes a page; Debian's chromium opens it from file:// with the network off, and the test checks that the page asks
// for nothing but itself, plays, shows at two slider positions exactly the states of michi's .path file, and draws
// something (the screenshots are not blank). It also opens the page of a `michi replan --html` episode: the executed
// state and the moving obstacles drawn where michi exported them at two slider positions.
//
// node browser_replay.js --michi BIN --problems DIR --out DIR --chromium PATH --modules NODE_MODULES
'use strict';
const {execFileSync} = require('child_process');
const fs = require('fs');
const path = require('path');
const {pathToFileURL} = require('url');

const args = {};
for (let i = 2; i + 1 < process.argv.length; i += 2) args[process.argv[i].replace(/^--/, '')] = process.argv[i + 1];
for (const key of ['michi', 'problems', 'out', 'chromium', 'modules']) {
    if (!args[key]) {
        console.error('browser_replay.js: missing --' + key);
        process.exit(2);
    }
}
const puppeteer = require(path.join(args.modules, 'puppeteer-core'));

const PLANNER = 'geometric::RRTConnect';
const TOLERANCE = 1e-6;
let failures = 0;
function check(ok, what) {
    console.log((ok ? 'ok   ' : 'FAIL ') + what);
    if (!ok) failures++;
}

/** The states of a .path file (PathFile.cpp: '#' lines, then one state a line). */
function readPath(file) {
    return fs.readFileSync(file, 'utf8').split('\n').filter((l) => l.trim() && !l.startsWith('#'))
        .map((l) => l.trim().split(/\s+/).map(Number));
}

/** A new tab with \e html opened from file:// with no network, once its viewer is ready: the DevTools protocol's
    offline mode, and every request that is not the page itself (or a data: URL it makes in memory) is failed and
    counted in \e blocked; script errors are collected in \e errors (and checked here once loaded). */
async function openOffline(browser, html, name) {
    const page = await browser.newPage();
    const url = pathToFileURL(html).href;
    const blocked = [];
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    page.on('console', (m) => {
        if (m.type() === 'error') errors.push(m.text());
    });
    await page.setOfflineMode(true);
    await page.setRequestInterception(true);
    page.on('request', (request) => {
        const u = request.url();
        if (u === url || u.startsWith('data:')) {
            request.continue();
        } else {
            blocked.push(u);
            request.abort();
        }
    });
    await page.setViewport({width: 1000, height: 700});
    await page.goto(url, {waitUntil: 'load'});
    await page.waitForFunction(() => window.michiViewer && window.michiViewer.ready, {timeout: 30000});
    check(errors.length === 0, name + ': no script error' + (errors.length ? ' (' + errors.join('; ') + ')' : ''));
    return {page, blocked, errors};
}

/** A screenshot of \e page saved as \e file, checked not blank (grey-level variance and colour count). */
async function checkScreenshot(page, file, name) {
    const png = Buffer.from(await page.screenshot({type: 'png'})).toString('base64');
    fs.writeFileSync(file, Buffer.from(png, 'base64'));
    // decode the screenshot in the page (a data: URL, allowed) and measure its pixels' spread
    const stats = await page.evaluate(async (b64) => {
        const image = new Image();
        image.src = 'data:image/png;base64,' + b64;
        await image.decode();
        const canvas = document.createElement('canvas');
        canvas.width = image.width;
        canvas.height = image.height;
        const c = canvas.getContext('2d');
        c.drawImage(image, 0, 0);
        const px = c.getImageData(0, 0, image.width, image.height).data;
        let sum = 0, sum2 = 0, n = 0;
        const colours = new Set();
        for (let i = 0; i < px.length; i += 4) {
            const g = 0.299 * px[i] + 0.587 * px[i + 1] + 0.114 * px[i + 2];
            sum += g;
            sum2 += g * g;
            n++;
            if (colours.size < 1000) colours.add((px[i] << 16) | (px[i + 1] << 8) | px[i + 2]);
        }
        const mean = sum / n;
        return {variance: sum2 / n - mean * mean, colours: colours.size};
    }, png);
    check(stats.variance > 50 && stats.colours > 20,
          name + ': screenshot ' + file + ' is not blank (grey variance ' + stats.variance.toFixed(1) + ', ' +
              stats.colours + ' colours)');
}

async function checkProblem(browser, name) {
    const out = path.join(args.out, name);
    fs.rmSync(out, {recursive: true, force: true});
    execFileSync(args.michi, ['plan', path.join(args.problems, name + '.yaml'), '--planner', PLANNER, '--time', '10',
                              '--seed', '1', '--html', '--out', out], {stdio: ['ignore', 'ignore', 'inherit']});
    const html = path.join(out, name + '.html');
    const expected = readPath(path.join(out, name + '-' + PLANNER.replace(/[^A-Za-z0-9_-]/g, '_') + '.path'));
    check(fs.existsSync(html), name + ': michi wrote ' + html);
    check(expected.length >= 2, name + ': the .path file has ' + expected.length + ' states');

    const {page, blocked, errors} = await openOffline(browser, html, name);

    // it plays: the clock advances by itself
    await page.evaluate(() => window.michiViewer.play());
    await new Promise((r) => setTimeout(r, 700));
    const played = await page.evaluate(() => window.michiViewer.getPose().time);
    await page.evaluate(() => window.michiViewer.pause());
    check(played > 0, name + ': playing moved the clock to ' + played.toFixed(3) + ' s');

    // two slider positions, set through the slider as a user would: halfway through the path (between waypoints
    // for a path of two), and the goal
    const times = await page.evaluate((n) => {
        const t = [];
        for (let k = 0; k < n; ++k) t.push(window.michiViewer.waypointTime(0, k));
        return t;
    }, expected.length);
    const kind = await page.evaluate(() => window.michiViewer.data.kind);
    const middle = expected.length > 2 ? times[Math.floor((expected.length - 1) / 2)] : times[times.length - 1] / 2;
    for (const [shot, t] of [['a', middle], ['b', times[times.length - 1]]]) {
        const pose = await page.evaluate((t) => {
            const slider = document.getElementById('slider');
            slider.value = String(t);
            slider.dispatchEvent(new Event('input', {bubbles: true}));
            return window.michiViewer.getPose();
        }, t);
        // michi's state at t from its .path file: a waypoint's row, or (joint space, where michi's interpolation is
        // linear) the blend of the two rows around t
        let k = times.findIndex((w) => Math.abs(w - t) <= 1e-9);
        let want;
        if (k >= 0) {
            want = expected[k];
        } else if (kind === 'arm') {
            k = times.findIndex((w) => w > t) - 1;
            const s = (t - times[k]) / (times[k + 1] - times[k]);
            want = expected[k].map((v, i) => v + s * (expected[k + 1][i] - v));
        } else {
            check(false, name + ': slider position ' + t + ' is not a waypoint of an SE(2) path');
            continue;
        }
        const state = pose.paths[0].state;
        const error = Math.max(...want.map((v, i) => Math.abs(v - state[i])));
        check(state.length === want.length && error <= TOLERANCE,
              name + ': at slider position ' + t.toFixed(3) + ' s the page shows michi\'s state (' +
                  (k >= 0 && Math.abs(times[k] - t) <= 1e-9 ? 'waypoint ' + k : 'between waypoints') + ', error ' +
                  error.toExponential(2) + ')');
        // what is drawn is what michi computed for that frame (at a frame the page blends nothing)
        const frame = await page.evaluate(() => {
            const v = window.michiViewer, p = v.data.paths[0], f = v.getPose().paths[0];
            return f.alpha === 0 ? p.poses[f.frame] : null;
        });
        if (frame) {
            let drawn = 0;
            pose.paths[0].bodies.forEach((b, j) => {
                for (let i = 0; i < 3; ++i) drawn = Math.max(drawn, Math.abs(b.position[i] - frame[7 * j + i]));
            });
            check(drawn <= 1e-9, name + ': the drawn bodies sit at michi\'s poses for that frame');
        }

        await checkScreenshot(page, path.join(args.out, name + '-' + shot + '.png'), name);
    }
    check(blocked.length === 0,
          name + ': no request left the page' + (blocked.length ? ' (' + blocked.join(', ') + ')' : ''));
    await page.close();
}

/** `michi replan --html`: the page of a replan episode. At two slider positions (frames a third and two thirds
    into the episode) the page shows the executed state michi exported for that frame and draws every moving
    obstacle at its key frame for that time; the obstacles are elsewhere at the two times. */
async function checkReplan(browser, name) {
    const out = path.join(args.out, 'replan_' + name);
    fs.rmSync(out, {recursive: true, force: true});
    execFileSync(args.michi, ['replan', path.join(args.problems, name + '.yaml'), '--episodes', '1', '--seed', '3',
                              '--methods', 'dual', '--html', '--out', out], {stdio: ['ignore', 'ignore', 'inherit']});
    const html = path.join(out, name + '.html');
    check(fs.existsSync(html), 'replan ' + name + ': michi wrote ' + html);
    const {page, blocked} = await openOffline(browser, html, 'replan ' + name);

    await page.evaluate(() => window.michiViewer.play());
    await new Promise((r) => setTimeout(r, 700));
    const played = await page.evaluate(() => window.michiViewer.getPose().time);
    await page.evaluate(() => window.michiViewer.pause());
    check(played > 0, 'replan ' + name + ': playing moved the clock to ' + played.toFixed(3) + ' s');

    const data = await page.evaluate(() => window.michiViewer.data);
    const path0 = data.paths[0];
    const movers = data.obstacles.filter((o) => o.trajectory.length > 1);
    check(movers.length > 0, 'replan ' + name + ': the page has ' + movers.length + ' moving obstacle(s)');
    const drawnAt = [];
    for (const [shot, fraction] of [['a', 1 / 3], ['b', 2 / 3]]) {
        const frame = Math.floor(fraction * (path0.times.length - 1));
        const t = path0.times[frame];
        const pose = await page.evaluate((t) => {
            const slider = document.getElementById('slider');
            slider.value = String(t);
            slider.dispatchEvent(new Event('input', {bubbles: true}));
            return window.michiViewer.getPose();
        }, t);
        const state = pose.paths[0].state;
        const error = Math.max(...path0.states[frame].map((v, i) => Math.abs(v - state[i])));
        check(pose.paths[0].frame === frame && error <= TOLERANCE,
              'replan ' + name + ': at ' + t.toFixed(3) + ' s the page shows the executed state of frame ' + frame +
                  ' (error ' + error.toExponential(2) + ')');
        let obstacleError = 0;
        for (const o of movers) {
            const key = o.trajectory.find((k) => Math.abs(k[0] - t) <= 1e-9);
            const drawn = pose.obstacles.find((d) => d.name === o.name);
            if (!key || !drawn) {
                obstacleError = Infinity;
                continue;
            }
            for (let i = 0; i < 3; ++i) obstacleError = Math.max(obstacleError, Math.abs(drawn.position[i] - key[1 + i]));
        }
        check(obstacleError <= TOLERANCE, 'replan ' + name + ': at ' + t.toFixed(3) +
                                              ' s every moving obstacle is drawn at its key frame (error ' +
                                              obstacleError.toExponential(2) + ')');
        drawnAt.push(pose.obstacles);
        await checkScreenshot(page, path.join(args.out, 'replan_' + name + '-' + shot + '.png'), 'replan ' + name);
    }
    const moved = drawnAt[0].some((o, i) => Math.hypot(o.position[0] - drawnAt[1][i].position[0],
                                                       o.position[1] - drawnAt[1][i].position[1]) > 0.05);
    check(moved, 'replan ' + name + ': the moving obstacles moved between the two slider positions');
    check(blocked.length === 0,
          'replan ' + name + ': no request left the page' + (blocked.length ? ' (' + blocked.join(', ') + ')' : ''));
    await page.close();
}

(async () => {
    fs.mkdirSync(args.out, {recursive: true});
    // root in a container: chromium's sandbox needs user namespaces it does not have; SwiftShader renders WebGL
    // without a GPU
    const browser = await puppeteer.launch({
        executablePath: args.chromium,
        headless: true,
        args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-dev-shm-usage',
               '--no-first-run', '--no-default-browser-check'],
    });
    try {
        for (const name of ['panda_table_pick', 'se2_corridor']) await checkProblem(browser, name);
        await checkReplan(browser, 'dynamic_mobile_passage');
    } finally {
        await browser.close();
    }
    console.log(failures ? failures + ' check(s) failed' : 'all checks passed');
    process.exit(failures ? 1 : 0);
})().catch((e) => {
    console.error('browser_replay.js: ' + (e && e.stack ? e.stack : e));
    process.exit(1);
});
