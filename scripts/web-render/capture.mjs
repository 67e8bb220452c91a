// In the page: renders each of the eval's views (`qf-render eval --cameras` JSON) over black and
// over white, so that `qf-render eval --external` can recover coverage from the pair, and reads the
// pixels back. Every engine script uses this loop; the engine supplies how to set a view and draw.
//   setView(view): place the camera (and the headlight) for one entry of cams.views
//   draw([r, g, b]): clear to that background (0..1) and draw the scene
// Returns, per view, [black, white] as base64 RGBA rows, top row first.
export function captureViews(gl, cams, setView, draw) {
  const out = [];
  for (const v of cams.views) {
    setView(v);
    const pair = [];
    for (const bg of [[0, 0, 0], [1, 1, 1]]) {
      draw(bg);
      const px = new Uint8Array(v.width * v.height * 4);
      gl.readPixels(0, 0, v.width, v.height, gl.RGBA, gl.UNSIGNED_BYTE, px);
      pair.push(base64TopDown(px, v.width, v.height));
    }
    out.push(pair);
  }
  return out;
}

// GL rows are bottom-up; base64 is what crosses to Node cheaply (a plain array of numbers costs
// seconds a file to serialise).
function base64TopDown(px, width, height) {
  const stride = width * 4;
  let s = '';
  for (let y = height - 1; y >= 0; --y) s += String.fromCharCode.apply(null, px.subarray(y * stride, (y + 1) * stride));
  return btoa(s);
}

// Collects what the engine's loader says through console.warn / console.error while `load` runs:
// a file must load without either.
export async function collectWarnings(load) {
  const warnings = [], warn = console.warn, error = console.error;
  console.warn = (...a) => { warnings.push(a.join(' ')); warn(...a); };
  console.error = (...a) => { warnings.push(a.join(' ')); error(...a); };
  try {
    return { result: await load(), warnings };
  } finally {
    console.warn = warn;
    console.error = error;
  }
}
