// The ray debugger on the game page. A click (or a tap) on the 3D view asks the server to debug
// that column ({"ray":C}); the server freezes this player's view (the world goes on) and answers
// with the ray in `halfcast trace`'s terms ({"ray":{pos,angle,column,size,fov,map}}), which the
// panel (ray.js) draws from /trace.json. Where the view is comes from the server's
// {"view":{x,y,cols,rows}}. The address then carries the ray, so `/?pos=…` opened in any browser
// shows it again, without playing. Moving the mouse over the view previews other columns.

import { mountRayPanel, queryFromRay, rayFromAddress } from "./ray.js";

// `link`: link.js's Link; `grid`: the canvas the cells are drawn on; `dock`: where the panel
// goes; `touch`: touch.js's Touch; `cols()`/`rows()`: the screen's size in cells.
export function wireRays({ link, grid, dock, touch, cols, rows }) {
  let where = null;
  let panel = null;

  // The view's column under the point (x, y) of the window, or null off the view.
  function columnAt(x, y) {
    if (!where) return null;
    const r = grid.getBoundingClientRect();
    if (!r.width || !r.height) return null;
    const cx = Math.floor(((x - r.left) / r.width) * cols());
    const cy = Math.floor(((y - r.top) / r.height) * rows());
    const inside = cx >= where.x && cx < where.x + where.cols && cy >= where.y && cy < where.y + where.rows;
    return inside ? cx - where.x : null;
  }

  function ask(x, y) {
    const c = columnAt(x, y);
    if (c !== null) link.send({ ray: c });
  }

  function open(query) {
    if (panel) {
      panel.show(query);
      return;
    }
    dock.classList.remove("hidden");
    panel = mountRayPanel(dock, {
      query,
      onShow: (address) => history.replaceState(null, "", `${location.pathname}?${address}`),
      onClose: () => {
        panel = null;
        dock.classList.add("hidden");
        history.replaceState(null, "", location.pathname);
        link.send({ ray: null });
      },
    });
  }

  link.on("view", (v) => { where = v; });
  link.on("ray", (r) => open(queryFromRay(r)));
  grid.parentElement.addEventListener("click", (e) => {
    if (e.pointerType !== "touch") ask(e.clientX, e.clientY);
  });
  touch.onViewTap = ask;
  grid.parentElement.addEventListener("mousemove", (e) => panel?.previewColumn(columnAt(e.clientX, e.clientY)));
  grid.parentElement.addEventListener("mouseleave", () => panel?.previewColumn(null));

  // A ray in the address (a shared link): shown at once, before or without playing.
  const shared = rayFromAddress(location);
  if (shared) open(shared);
  return { open, columnAt, get view() { return where; }, get panel() { return panel; } };
}
