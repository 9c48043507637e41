// The replay page's script (tools/src/viewer/page/replay.js, inlined into every page by michi; docs/viewer.md).
// It builds a three.js scene from the JSON michi wrote (#michi-data) and plays the paths. Every pose comes from michi
// (forward kinematics of the URDF, or the SE(2) footprint's placement); the page only interpolates between frames.
// window.michiViewer is the API scripts and tests use: setTime(t), getPose(), play(), pause(), ...
(function () {
    'use strict';
    const COLOURS = ['#e6194b', '#3cb44b', '#4363d8', '#f58231', '#911eb4', '#42d4f4', '#f032e6', '#9a6324'];
    // a slider position this close to a frame's time shows that frame exactly (its state as michi wrote it)
    const SNAP = 1e-9;
    const data = JSON.parse(document.getElementById('michi-data').textContent);

    const view = document.getElementById('view');
    const renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    renderer.setSize(view.clientWidth, view.clientHeight);
    renderer.setClearColor(0xf4f5f7);
    view.appendChild(renderer.domElement);

    const scene = new THREE.Scene();
    const camera = new THREE.PerspectiveCamera(45, view.clientWidth / view.clientHeight, 0.01, 1000);
    camera.up.set(0, 0, 1);  // robots live in z-up worlds (URDF, ROS)
    scene.add(new THREE.HemisphereLight(0xffffff, 0x666666, 0.75));
    const sun = new THREE.DirectionalLight(0xffffff, 0.6);
    sun.position.set(3, -2, 5);
    scene.add(sun);

    // ---- shapes: one geometry per shape of the page, shared by every object that uses it
    const geometries = [];
    function geometryOf(index) {
        if (geometries[index]) return geometries[index];
        const s = data.shapes[index];
        let parts;  // [[geometry, z offset]]: a capsule is a cylinder and two spheres
        if (s.type === 'box') {
            parts = [[new THREE.BoxBufferGeometry(s.size[0], s.size[1], s.size[2]), 0]];
        } else if (s.type === 'sphere') {
            parts = [[new THREE.SphereBufferGeometry(s.radius, 24, 16), 0]];
        } else if (s.type === 'cylinder' || s.type === 'capsule') {
            const c = new THREE.CylinderBufferGeometry(s.radius, s.radius, s.length, 24);
            c.rotateX(Math.PI / 2);  // three.js cylinders run along y, michi's (and URDF's) along z
            parts = [[c, 0]];
            if (s.type === 'capsule') {
                const ball = new THREE.SphereBufferGeometry(s.radius, 24, 16);
                parts.push([ball, s.length / 2], [ball, -s.length / 2]);
            }
        } else if (s.type === 'mesh') {
            const indexed = new THREE.BufferGeometry();
            indexed.setAttribute('position', new THREE.Float32BufferAttribute(s.vertices, 3));
            indexed.setIndex(s.vertices.length / 3 > 65535 ? new THREE.Uint32BufferAttribute(s.triangles, 1)
                                                           : new THREE.Uint16BufferAttribute(s.triangles, 1));
            // one normal per face: collision meshes and extruded walls have sharp edges, and shared vertices'
            // averaged normals would round them off
            const g = indexed.toNonIndexed();
            g.computeVertexNormals();
            parts = [[g, 0]];
        } else {
            throw new Error('unknown shape type ' + s.type);
        }
        geometries[index] = parts;
        return parts;
    }

    function setPose(object, p, offset) {
        const o = offset || 0;
        object.position.set(p[o], p[o + 1], p[o + 2]);
        object.quaternion.set(p[o + 3], p[o + 4], p[o + 5], p[o + 6]);
    }

    function shapeObject(index, material, pose) {
        const group = new THREE.Group();
        for (const [geometry, z] of geometryOf(index)) {
            const mesh = new THREE.Mesh(geometry, material);
            mesh.position.z = z;
            group.add(mesh);
        }
        if (pose) setPose(group, pose);
        return group;
    }

    function material(colour, opacity) {
        return new THREE.MeshLambertMaterial({
            color: colour, side: THREE.DoubleSide, transparent: opacity < 1, opacity: opacity,
        });
    }

    // ---- the world: obstacles (moving ones follow their key frames), an occupancy map, the robot's fixed links
    const obstacleMaterial = material(0x9aa3ad, 1);
    const moving = [];
    for (const o of data.obstacles) {
        const object = shapeObject(o.shape, obstacleMaterial, o.pose);
        object.name = o.name;
        scene.add(object);
        if (o.trajectory.length) moving.push({object: object, keys: o.trajectory});
    }
    if (data.map) scene.add(mapPlane(data.map));
    const fixedMaterial = material(0xc8c8c8, 1);
    for (const [shape, pose] of data.fixedParts) scene.add(shapeObject(shape, fixedMaterial, pose));

    function mapPlane(map) {
        const pixels = new Uint8Array(map.width * map.height * 4);
        let cell = 0, occupied = false;
        for (const run of map.runs) {
            const grey = occupied ? 60 : 238;
            for (let k = 0; k < run; ++k, ++cell) {
                pixels.set([grey, grey, grey, 255], cell * 4);
            }
            occupied = !occupied;
        }
        // rows from the lowest y up, as the plane's v coordinate runs
        const texture = new THREE.DataTexture(pixels, map.width, map.height, THREE.RGBAFormat);
        texture.magFilter = THREE.NearestFilter;
        texture.minFilter = THREE.LinearFilter;
        texture.needsUpdate = true;
        const w = map.width * map.resolution, h = map.height * map.resolution;
        const plane = new THREE.Mesh(new THREE.PlaneBufferGeometry(w, h),
                                     new THREE.MeshBasicMaterial({map: texture, side: THREE.DoubleSide}));
        plane.position.set(map.origin[0] + w / 2, map.origin[1] + h / 2, 0);
        plane.name = 'occupancy map';
        return plane;
    }

    // ---- the paths: per path the robot's bodies, the end-effector trace and a toggle
    const paths = data.paths.map(function (p, i) {
        const colour = COLOURS[i % COLOURS.length];
        const root = new THREE.Group();
        const bodyMaterial = material(colour, 1);
        const bodies = data.bodies.map(function (b) {
            const body = new THREE.Group();
            body.name = b.name;
            for (const [shape, pose] of b.parts) body.add(shapeObject(shape, bodyMaterial, pose));
            root.add(body);
            return body;
        });
        scene.add(root);
        let trace = null;
        if (data.endBody >= 0) {
            const points = [];
            const lift = data.kind === 'se2' ? 0.01 : 0;  // above the map plane
            for (const frame of p.poses) {
                const o = data.endBody * 7;
                points.push(frame[o], frame[o + 1], frame[o + 2] + lift);
            }
            const g = new THREE.BufferGeometry();
            g.setAttribute('position', new THREE.Float32BufferAttribute(points, 3));
            trace = new THREE.Line(g, new THREE.LineBasicMaterial({color: colour}));
            scene.add(trace);
        }
        return {data: p, colour: colour, root: root, bodies: bodies, trace: trace, visible: true, frame: 0,
                alpha: 0, state: p.states[0]};
    });
    const duration = paths.reduce(function (d, p) {
        return Math.max(d, p.data.times[p.data.times.length - 1]);
    }, 0);

    // ---- the clock
    let time = 0, playing = false, last = null;
    const slider = document.getElementById('slider');
    const clock = document.getElementById('clock');
    const playButton = document.getElementById('play');
    slider.max = String(duration > 0 ? duration : 1);

    /** The frame at or before t and how far towards the next one (0..1). */
    function locate(times, t) {
        let lo = 0, hi = times.length - 1;
        if (t >= times[hi] - SNAP) return [hi, 0];
        while (hi - lo > 1) {
            const mid = (lo + hi) >> 1;
            if (times[mid] <= t + SNAP) lo = mid; else hi = mid;
        }
        if (Math.abs(t - times[lo]) <= SNAP) return [lo, 0];
        return [lo, (t - times[lo]) / (times[lo + 1] - times[lo])];
    }

    const qa = new THREE.Quaternion(), qb = new THREE.Quaternion();
    function posePath(p, t) {
        const [i, alpha] = locate(p.data.times, t);
        const a = p.data.poses[i], b = p.data.poses[Math.min(i + 1, p.data.poses.length - 1)];
        p.bodies.forEach(function (body, k) {
            const o = k * 7;
            if (alpha === 0) {
                setPose(body, a, o);
                return;
            }
            body.position.set(a[o] + alpha * (b[o] - a[o]), a[o + 1] + alpha * (b[o + 1] - a[o + 1]),
                              a[o + 2] + alpha * (b[o + 2] - a[o + 2]));
            qa.set(a[o + 3], a[o + 4], a[o + 5], a[o + 6]);
            qb.set(b[o + 3], b[o + 4], b[o + 5], b[o + 6]);
            THREE.Quaternion.slerp(qa, qb, body.quaternion, alpha);
        });
        const sa = p.data.states[i], sb = p.data.states[Math.min(i + 1, p.data.states.length - 1)];
        p.frame = i;
        p.alpha = alpha;
        // between frames the state is a straight blend, for display only; at a frame it is michi's own
        p.state = alpha === 0 ? sa.slice() : sa.map(function (v, k) {
            return v + alpha * (sb[k] - v);
        });
    }

    function poseObstacles(t) {
        for (const m of moving) {
            const keys = m.keys;
            let i = 0;
            while (i + 1 < keys.length && keys[i + 1][0] <= t) ++i;
            if (i + 1 >= keys.length || t <= keys[0][0]) {
                setPose(m.object, keys[t <= keys[0][0] ? 0 : keys.length - 1], 1);  // held outside the key frames
                continue;
            }
            const a = keys[i], b = keys[i + 1], alpha = (t - a[0]) / (b[0] - a[0]);
            m.object.position.set(a[1] + alpha * (b[1] - a[1]), a[2] + alpha * (b[2] - a[2]),
                                  a[3] + alpha * (b[3] - a[3]));
            qa.set(a[4], a[5], a[6], a[7]);
            qb.set(b[4], b[5], b[6], b[7]);
            THREE.Quaternion.slerp(qa, qb, m.object.quaternion, alpha);
        }
    }

    function setTime(t) {
        time = Math.min(Math.max(Number(t) || 0, 0), duration);
        for (const p of paths) posePath(p, time);
        poseObstacles(time);
        slider.value = String(time);
        clock.textContent = time.toFixed(2) + ' s';
        render();
        return time;
    }

    function render() {
        renderer.render(scene, camera);
    }

    function play() {
        if (time >= duration) setTime(0);
        playing = true;
        last = null;
        playButton.textContent = 'Pause';
    }

    function pause() {
        playing = false;
        playButton.textContent = 'Play';
    }

    function tick(now) {
        if (playing) {
            if (last !== null) setTime(time + (now - last) / 1000);
            last = now;
            if (time >= duration) pause();
        }
        controls.update();
        render();
        requestAnimationFrame(tick);
    }

    // ---- controls: buttons, slider, one toggle per path
    playButton.addEventListener('click', function () {
        if (playing) pause(); else play();
    });
    slider.addEventListener('input', function () {
        pause();
        setTime(parseFloat(slider.value));
    });
    window.addEventListener('keydown', function (e) {
        if (e.code === 'Space' && e.target === document.body) {
            e.preventDefault();
            if (playing) pause(); else play();
        }
    });
    const list = document.getElementById('planners');
    paths.forEach(function (p, i) {
        const label = document.createElement('label');
        label.className = 'planner';
        const box = document.createElement('input');
        box.type = 'checkbox';
        box.checked = true;
        box.dataset.path = String(i);
        box.addEventListener('change', function () {
            setVisible(i, box.checked);
        });
        const swatch = document.createElement('span');
        swatch.className = 'swatch';
        swatch.style.background = p.colour;
        label.append(box, swatch, document.createTextNode(p.data.label));
        list.appendChild(label);
    });
    document.getElementById('title').textContent =
        data.problem + (paths.length ? '' : ' (no path to replay)');

    function setVisible(i, visible) {
        const p = paths[i];
        p.visible = !!visible;
        p.root.visible = p.visible;
        if (p.trace) p.trace.visible = p.visible;
        render();
    }

    // ---- camera: framing everything drawn, from the front-right and above; from nearly straight above for robots
    // that move in the plane (SE(2), planar arms), which tall obstacles would hide from the side
    const bounds = new THREE.Box3().setFromObject(scene);
    const centre = bounds.getCenter(new THREE.Vector3());
    const radius = Math.max(bounds.getSize(new THREE.Vector3()).length() / 2, 0.1);
    const direction = data.planar ? new THREE.Vector3(0, -0.55, 1) : new THREE.Vector3(1.2, -1.0, 0.8);
    camera.position.copy(centre).add(direction.normalize().multiplyScalar(radius * 2.2));
    camera.near = radius / 100;
    camera.far = radius * 50;
    camera.updateProjectionMatrix();
    const controls = new THREE.OrbitControls(camera, renderer.domElement);
    controls.target.copy(centre);
    controls.screenSpacePanning = true;
    controls.update();

    window.addEventListener('resize', function () {
        camera.aspect = view.clientWidth / view.clientHeight;
        camera.updateProjectionMatrix();
        renderer.setSize(view.clientWidth, view.clientHeight);
        render();
    });

    function getPose() {
        return {
            time: time,
            playing: playing,
            paths: paths.map(function (p) {
                return {
                    label: p.data.label, visible: p.visible, frame: p.frame, alpha: p.alpha, state: p.state.slice(),
                    // read back from the scene graph: what is drawn, not what was meant to be
                    bodies: p.bodies.map(function (b) {
                        return {name: b.name, position: b.position.toArray(), quaternion: b.quaternion.toArray()};
                    }),
                };
            }),
            // the moving obstacles as drawn (key frames blended at the clock's time)
            obstacles: moving.map(function (m) {
                return {name: m.object.name, position: m.object.position.toArray(),
                        quaternion: m.object.quaternion.toArray()};
            }),
        };
    }

    setTime(0);
    window.michiViewer = {
        data: data, duration: duration, setTime: setTime, getPose: getPose, play: play, pause: pause,
        setVisible: setVisible, render: render, isPlaying: function () {
            return playing;
        },
        /** The time at which path \e path reaches its waypoint \e k (a row of michi's .path file). */
        waypointTime: function (path, k) {
            const p = paths[path].data;
            return p.times[p.waypoints[k]];
        },
        ready: true,
    };
    requestAnimationFrame(tick);
})();
