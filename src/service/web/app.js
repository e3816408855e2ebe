// The page's entry point: hash routing between the views.
//   #/new[?example=<id>|from=<job id>]   new job form
//   #/jobs[?kind=&status=&offset=]       past jobs
//   #/jobs/<id>                          one job: progress, result, drawing, charts
//   #/db/<table>                         the cutting-condition database
import { h, problemBox, askForKey } from './ui.js';
import { newJobView } from './new-job.js';
import { jobView } from './job-view.js';
import { jobsView } from './jobs.js';
import { databaseView } from './database.js';
import { unitsSwitch } from './units.js';

const main = document.getElementById('main');
let cleanup = null;
let generation = 0;

function parseHash() {
  const raw = location.hash.replace(/^#\/?/, '');
  const [path, query = ''] = raw.split('?');
  return { parts: path.split('/').filter(Boolean).map(decodeURIComponent), params: new URLSearchParams(query) };
}

function setActiveNav(section) {
  for (const link of document.querySelectorAll('[data-nav]')) {
    if (link.dataset.nav === section) link.setAttribute('aria-current', 'page');
    else link.removeAttribute('aria-current');
  }
}

/** Renders the view of the current hash; `refresh` keeps the scroll position. */
async function route(refresh = false) {
  if (cleanup) {
    try { cleanup(); } catch (err) { console.warn(err); }
    cleanup = null;
  }
  const mine = ++generation;
  const { parts, params } = parseHash();
  const section = parts[0] || 'new';
  setActiveNav(section);
  const view = {
    new: () => newJobView(params),
    jobs: () => (parts[1] ? jobView(parts[1]) : jobsView(params)),
    db: () => databaseView(parts[1] || 'tools', params),
  }[section];
  if (!view) {
    location.replace('#/new');
    return;
  }
  const container = h('div', { class: 'view' });
  if (refresh && main.firstChild) {
    // Keep the old content until the new one is ready (no flicker, no jump).
    container.append(...main.firstChild.childNodes);
  }
  main.replaceChildren(container);
  try {
    const result = await view();
    if (mine !== generation) {
      if (result?.cleanup) result.cleanup();
      return;
    }
    const scroll = window.scrollY;
    container.replaceChildren(result.node);
    cleanup = result.cleanup || null;
    if (refresh) window.scrollTo(0, scroll);
    else window.scrollTo(0, 0);
    if (result.title) document.title = `${result.title} · dieplan`;
  } catch (err) {
    if (mine !== generation) return;
    container.replaceChildren(problemBox(err, 'This page could not be loaded'));
  }
}

// The skip link focuses the content without touching the route in the hash.
document.querySelector('.skip')?.addEventListener('click', (event) => {
  event.preventDefault();
  main.focus();
});
window.addEventListener('hashchange', () => route(false));
// Views ask for a refresh of themselves (after an edit, or while jobs run).
window.addEventListener('dieplan:refresh', () => route(true));
if (!location.hash) history.replaceState(null, '', '#/new');
route(false);

// mm or inch: what the page shows (the API stays in mm).
document.getElementById('units-slot')?.replaceChildren(unitsSwitch());

// "API key" in the header: enter, change or forget the key this browser sends.
document.getElementById('api-key-button')?.addEventListener('click', async () => {
  const key = await askForKey('Enter the API key this browser sends with every request, or forget the stored one.');
  if (key !== null) route(true);
});
