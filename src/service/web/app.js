// The page's entry point: hash routing between the views.
//   #/new[?example=<id>|from=<job id>]   new job form
//   #/jobs[?kind=&status=&offset=]       past jobs
//   #/jobs/<id>                          one job: progress, result, drawing, charts
//   #/db/<table>                         the cutting-condition database
import { h, problemBox } from './ui.js';
import { newJobView } from './new-job.js';
import { jobView } from './job-view.js';
import { jobsView } from './jobs.js';
import { databaseView } from './database.js';

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

async function route() {
  if (cleanup) {
    try { cleanup(); } catch (err) { console.warn(err); }
    cleanup = null;
  }
  const mine = ++generation;
  const { parts, params } = parseHash();
  const section = parts[0] || 'new';
  setActiveNav(section === 'db' ? 'db' : section === 'jobs' && parts[1] ? 'jobs' : section);
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
  main.replaceChildren(container);
  try {
    const result = await view();
    if (mine !== generation) {
      if (result?.cleanup) result.cleanup();
      return;
    }
    container.replaceChildren(result.node);
    cleanup = result.cleanup || null;
    if (result.title) document.title = `${result.title} · dieplan`;
  } catch (err) {
    if (mine !== generation) return;
    container.replaceChildren(problemBox(err, 'This page could not be loaded'));
  }
}

window.addEventListener('hashchange', route);
if (!location.hash) location.replace('#/new');
route();
