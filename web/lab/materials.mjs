// How the 3D view colours and lights a model as MuJoCo's renderer does: materials from the
// model's mat_* arrays (rgba, specular, shininess, emission, the rgb texture with its
// repeat), textures from tex_data (builtin patterns and PNG files, compiled by the engine),
// the skybox, a checker on planes that have no material, and the headlight with the
// model's own lights. Colours are used as MuJoCo uses them: no colour management (see
// LabScene), so an rgba of 0.5 is drawn as 0.5.
import * as THREE from '../node_modules/three/build/three.module.js';

// mjtTexture and mjtLightType numbers, the rgb texture role.
const kTexture2D = 0, kTextureCube = 1, kTextureSkybox = 2;
const kLightDirectional = 1, kLightPoint = 2;
const kRoleRgb = 1, kNumRoles = 10;
const kPlane = 0;
// MuJoCo's geom colour when none is given: a material's rgba then wins.
const kDefaultRgba = [0.5, 0.5, 0.5, 1];
// three.js divides diffuse light by pi (a physical Lambert surface): lights are scaled by
// pi so that a light of diffuse d adds d x colour to a surface facing it, as in MuJoCo.
const kLightScale = Math.PI;

// ---------------------------------------------------------------- textures

// The pixels of texture `t` as RGBA (alpha opaque where the texture has none): a 2D
// texture's whole image (face null), or face `face` (width x width) of a cube texture.
function textureRgba(model, t, face) {
  const width = model.tex_width[t], nchannel = model.tex_nchannel[t];
  const height = face === null ? model.tex_height[t] : width;
  const start = model.tex_adr[t] + (face ?? 0) * width * width * nchannel;
  const out = new Uint8Array(4 * width * height);
  for (let p = 0; p < width * height; p++) {
    const at = start + p * nchannel;
    if (nchannel === 1) {
      out.fill(model.tex_data[at], 4 * p, 4 * p + 3);
    } else {
      for (let k = 0; k < 3; k++) out[4 * p + k] = model.tex_data[at + k];
    }
    out[4 * p + 3] = nchannel === 4 ? model.tex_data[at + 3] : 255;
  }
  return { out, width, height };
}

// A three.js texture of 2D texture `t` (rows from the top, as the image), repeating.
function texture2D(model, t) {
  const { out, width, height } = textureRgba(model, t, null);
  const texture = new THREE.DataTexture(out, width, height, THREE.RGBAFormat);
  texture.flipY = false;
  texture.wrapS = texture.wrapT = THREE.RepeatWrapping;
  texture.magFilter = THREE.LinearFilter;
  texture.minFilter = THREE.LinearMipmapLinearFilter;
  texture.generateMipmaps = true;
  texture.needsUpdate = true;
  return texture;
}

// The six faces of a cube or skybox texture as a three.js cube texture (faces in
// MuJoCo's order right, left, up, down, front, back, which is OpenGL's +x, -x, +y, -y,
// +z, -z, as three.js expects). A texture of one face repeats it six times.
function cubeTexture(model, t) {
  const faces = model.tex_height[t] >= 6 * model.tex_width[t] ? 6 : 1;
  const images = [];
  for (let f = 0; f < 6; f++) {
    const { out, width } = textureRgba(model, t, faces === 6 ? f : 0);
    images.push(new THREE.DataTexture(out, width, width, THREE.RGBAFormat));
  }
  // (three.js uploads a cube texture of data textures face by face, as raw pixels)
  const texture = new THREE.CubeTexture(images);
  texture.format = THREE.RGBAFormat;
  texture.flipY = false;
  texture.generateMipmaps = false;
  texture.minFilter = THREE.LinearFilter;
  texture.needsUpdate = true;
  return texture;
}

// Draws a cube texture on a geom as MuJoCo does: the texel is looked up in the
// direction of the surface point from the geom's centre (its object coordinates), and
// multiplies the surface colour. three.js has no such mapping, so the Phong shader gets
// it (material.onBeforeCompile).
function addCubeMap(material, cube) {
  material.userData.cubeMap = cube;
  material.onBeforeCompile = (shader) => {
    shader.uniforms.geomCubeMap = { value: cube };
    shader.vertexShader = shader.vertexShader
      .replace('#include <common>', '#include <common>\nvarying vec3 vObjectPosition;')
      .replace('#include <begin_vertex>', '#include <begin_vertex>\nvObjectPosition = position;');
    shader.fragmentShader = shader.fragmentShader
      .replace('#include <common>', '#include <common>\nuniform samplerCube geomCubeMap;\nvarying vec3 vObjectPosition;')
      .replace('#include <map_fragment>',
               '#include <map_fragment>\ndiffuseColor.rgb *= textureCube(geomCubeMap, vObjectPosition).rgb;');
  };
  material.customProgramCacheKey = () => 'simlab-geom-cube-map';
}

// A light grey checker for planes drawn without a material, so that distances and motion
// along the floor can be read: two tones of the plane's colour, one square per metre
// when texrepeat-like scaling is applied by the caller.
function checkerTexture(rgba) {
  const tone = (scale) => rgba.slice(0, 3).map((c) => Math.round(255 * Math.min(1, c * scale)));
  const [light, dark] = [tone(1.12), tone(0.88)];
  const data = new Uint8Array(4 * 4);
  [light, dark, dark, light].forEach((c, p) => data.set([...c, 255], 4 * p));
  const texture = new THREE.DataTexture(data, 2, 2, THREE.RGBAFormat);
  texture.wrapS = texture.wrapT = THREE.RepeatWrapping;
  texture.magFilter = THREE.NearestFilter;
  texture.needsUpdate = true;
  return texture;
}

// ---------------------------------------------------------------- materials

export class Materials {
  constructor(model) {
    this.model = model;
    this.textures = new Map();  // texture id -> three.js texture (made once)
    this.repeats = new Map();   // "material:repeat" -> that texture with the material's repeat
  }

  texture(t) {
    if (!this.textures.has(t)) {
      const m = this.model;
      this.textures.set(t, m.tex_type[t] === kTexture2D ? texture2D(m, t) : cubeTexture(m, t));
    }
    return this.textures.get(t);
  }

  // Frees every texture made (the GPU side).
  dispose() {
    for (const texture of [...this.textures.values(), ...this.repeats.values()]) texture.dispose();
  }

  // The skybox: the first skybox texture, as the scene's background (z up), or null.
  skybox() {
    const type = this.model.tex_type ?? [];
    for (let t = 0; t < type.length; t++) {
      if (type[t] === kTextureSkybox) return this.texture(t);
    }
    return null;
  }

  // The surface of geom g: MuJoCo's rule for rgba (the geom's own colour wins over its
  // material's when it is not the default), then the material's specular, shininess,
  // emission and rgb texture (a 2D one; texrepeat per unit length with texuniform on
  // planes, across the geom otherwise). `size` is the plane's drawn half size; hasUv says
  // whether the geometry has texture coordinates.
  geomMaterial(g, size, hasUv = true) {
    const m = this.model;
    const own = Array.from(m.geom_rgba.subarray(4 * g, 4 * g + 4));
    const mat = m.geom_matid?.[g] ?? -1;
    const isDefault = own.every((v, k) => Math.abs(v - kDefaultRgba[k]) < 1e-6);
    const rgba = mat >= 0 && isDefault ? Array.from(m.mat_rgba.subarray(4 * mat, 4 * mat + 4)) : own;
    const surface = mat >= 0 ? { specular: m.mat_specular[mat], shininess: m.mat_shininess[mat],
                                 emission: m.mat_emission[mat] }
      : { specular: 0.5, shininess: 0.5, emission: 0 };
    // MuJoCo hands OpenGL shininess x 128, whose highlight peaks at light specular x
    // material specular; three.js normalizes Blinn-Phong ((s/2 + 1)/4 at the peak) and
    // lights highlights with the diffuse colour: the specular colour is scaled back so
    // that the peak is about MuJoCo's (its lights' specular is about half their diffuse).
    const shininess = 128 * surface.shininess;
    const specular = surface.specular * 0.5 * 4 / (shininess / 2 + 1);
    const params = {
      color: new THREE.Color(rgba[0], rgba[1], rgba[2]),
      specular: new THREE.Color(specular, specular, specular),
      shininess,
      emissive: new THREE.Color(rgba[0], rgba[1], rgba[2]).multiplyScalar(surface.emission),
      opacity: rgba[3], transparent: rgba[3] < 1, depthWrite: rgba[3] >= 1,
      flatShading: m.geom_type[g] === 7,
    };
    const tex = mat >= 0 ? m.mat_texid[kNumRoles * mat + kRoleRgb] : -1;
    // (a mesh without texture coordinates shows its material's colour only)
    if (tex >= 0 && m.tex_type[tex] === kTexture2D && hasUv) {
      params.map = this.repeated(this.texture(tex), mat, m.geom_type[g] === kPlane ? size : null);
    } else if (tex < 0 && mat < 0 && m.geom_type[g] === kPlane) {
      params.map = checkerTexture(rgba);
      // (one checker pair per metre, the map applied over the plane's full size)
      params.map.repeat.set(size[0], size[1]);
    }
    const material = new THREE.MeshPhongMaterial(params);
    if (tex >= 0 && m.tex_type[tex] === kTextureCube) addCubeMap(material, this.texture(tex));
    return material;
  }

  // `texture` with material mat's repeat: per unit length on a plane of half size `size`
  // when texuniform, else over the whole surface. Geoms with the same repeat share one
  // copy (one upload).
  repeated(texture, mat, size) {
    const m = this.model;
    const [rx, ry] = [m.mat_texrepeat[2 * mat], m.mat_texrepeat[2 * mat + 1]];
    const repeat = size && m.mat_texuniform[mat] ? [2 * size[0] * rx, 2 * size[1] * ry] : [rx, ry];
    const key = `${mat}:${repeat.join(',')}`;
    if (!this.repeats.has(key)) {
      const copy = texture.clone();
      copy.needsUpdate = true;
      copy.repeat.set(repeat[0], repeat[1]);
      this.repeats.set(key, copy);
    }
    return this.repeats.get(key);
  }
}

// ---------------------------------------------------------------- lights

// The headlight (a light at the camera, along its view, plus ambient light) and one
// three.js light per active model light; `update(state)` moves the model's lights to
// light_xpos/light_xdir. Directional and spot lights cast shadows when the model says so.
export class Lights {
  constructor(scene, camera, model, visual, extent) {
    this.model = model;
    this.lights = [];
    const head = visual?.headlight ?? { ambient: [0.1, 0.1, 0.1], diffuse: [0.4, 0.4, 0.4], active: 1 };
    let ambient = new THREE.Color(...head.ambient);
    if (head.active) {
      this.headlight = new THREE.DirectionalLight(new THREE.Color(...head.diffuse), kLightScale);
      this.headlight.position.set(0, 0, 0);
      this.headlight.target.position.set(0, 0, -1);
      camera.add(this.headlight);
      camera.add(this.headlight.target);
      scene.add(camera);
    } else {
      ambient = new THREE.Color(0, 0, 0);
    }
    const count = model.light_type?.length ?? 0;
    for (let i = 0; i < count; i++) {
      ambient.add(new THREE.Color(...model.light_ambient.subarray(3 * i, 3 * i + 3)));
      if (!model.light_active[i]) continue;
      const light = this.makeLight(i, extent);
      scene.add(light);
      if (light.target) scene.add(light.target);
      this.lights.push({ i, light });
    }
    this.ambient = new THREE.AmbientLight(ambient, kLightScale);
    scene.add(this.ambient);
  }

  // Moves the headlight (and its target) onto `camera`, the camera about to draw.
  attachHeadlight(camera) {
    if (!this.headlight || this.headlight.parent === camera) return;
    camera.add(this.headlight);
    camera.add(this.headlight.target);
  }

  makeLight(i, extent) {
    const m = this.model;
    const color = new THREE.Color(...m.light_diffuse.subarray(3 * i, 3 * i + 3));
    let light;
    if (m.light_type[i] === kLightDirectional) {
      light = new THREE.DirectionalLight(color, kLightScale);
    } else if (m.light_type[i] === kLightPoint) {
      light = new THREE.PointLight(color, kLightScale, 0, 0);
    } else {
      // A spot: its cone half angle is cutoff; the exponent softens the edge.
      const cutoff = Math.min(89, m.light_cutoff[i]) * Math.PI / 180;
      light = new THREE.SpotLight(color, kLightScale, 0, cutoff, Math.min(1, m.light_exponent[i] / 20), 0);
    }
    if (m.light_castshadow[i] && !(light instanceof THREE.PointLight)) {
      light.castShadow = true;
      light.shadow.mapSize.set(1024, 1024);
      light.shadow.bias = -0.0005;
      const cam = light.shadow.camera;
      if (cam.isOrthographicCamera) {
        cam.left = cam.bottom = -extent;
        cam.right = cam.top = extent;
      }
      cam.near = 0.01 * extent;
      cam.far = 20 * extent;
    }
    return light;
  }

  // Places the model's lights from the state (light_xpos, light_xdir views).
  update(state) {
    if (!state.light_xpos) return;
    for (const { i, light } of this.lights) {
      const p = state.light_xpos, d = state.light_xdir;
      light.position.set(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
      if (light.target) {
        light.target.position.set(p[3 * i] + d[3 * i], p[3 * i + 1] + d[3 * i + 1], p[3 * i + 2] + d[3 * i + 2]);
        light.target.updateMatrixWorld();
      }
    }
  }
}
