// The 3-D view's card on a finished job's page. three.js (2 MB, vendored under
// /vendor/three/) is loaded only when the view is opened: `view3d.js` imports it.
import { h, api, problemBox } from './ui.js';

// The job whose 3-D view was last opened: the page draws itself again when the display
// unit changes, and the view opens again with it.
let openedFor = null;

/** The card, or null for a job with nothing to draw. */
export function view3dPanel(job) {
  if (!job.links?.views) return null;
  const body = h('div', { class: 'view3d-body' });
  const open = h('button', { type: 'button', class: 'primary', id: 'open-3d', onclick: async () => {
    open.disabled = true;
    openedFor = job.id;
    body.replaceChildren(h('p', { class: 'muted' }, 'Loading the 3-D view…'));
    try {
      const [{ view3d }, views] = await Promise.all([import('./view3d.js'), api('GET', job.links.views)]);
      open.remove();
      body.replaceChildren(view3d(job, views));
    } catch (err) {
      open.disabled = false;
      body.replaceChildren(problemBox(err, 'Could not open the 3-D view'));
    }
  } }, 'Show in 3-D');
  if (openedFor === job.id) requestAnimationFrame(() => open.click());
  return h('section', { class: 'card view3d-card', id: 'view3d-card' }, h('h2', {}, '3-D view'),
    h('p', { class: 'hint' }, 'The stock the job left (analysis, costing, side-milling feeds, trochoids and plan jobs keep it) and the tool path in 3-D, coloured as in the drawing; play the path with the time slider.'),
    open, body);
}
