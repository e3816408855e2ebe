// The API key of this browser: kept in localStorage, sent as `Authorization: Bearer` by
// api() in ui.js, and asked for when the service answers 401 (or when "API key" in the
// header is clicked). A service without keys never asks.

const STORAGE = 'dieplan.apiKey';
let pending = null;

/** The stored key, or '' when there is none (or storage is blocked). */
export function storedKey() {
  try { return localStorage.getItem(STORAGE) || ''; } catch { return ''; }
}

function storeKey(key) {
  try {
    if (key) localStorage.setItem(STORAGE, key);
    else localStorage.removeItem(STORAGE);
  } catch { /* private mode: the key lasts for this page only */ }
}

function el(tag, attrs = {}, ...children) {
  const node = document.createElement(tag);
  for (const [name, value] of Object.entries(attrs)) node.setAttribute(name, value);
  node.append(...children);
  return node;
}

/**
 * Asks for a key in a dialog; resolves to the key entered (stored), '' when the user
 * chose to forget it, or null when cancelled. Concurrent callers share one dialog.
 */
export function askForKey(reason) {
  if (pending) return pending;
  pending = new Promise((resolve) => {
    const input = el('input', { type: 'password', id: 'api-key-input', name: 'key', autocomplete: 'off', spellcheck: 'false', placeholder: 'dpk_…', required: '' });
    const use = el('button', { type: 'submit', class: 'primary', value: 'use' }, 'Use this key');
    const forget = el('button', { type: 'button', class: 'link' }, 'Forget the stored key');
    const cancel = el('button', { type: 'button' }, 'Cancel');
    const form = el('form', { method: 'dialog' },
      el('h2', {}, 'API key'),
      el('p', {}, reason || 'This service needs an API key.'),
      el('p', { class: 'muted' }, 'Ask your dieplan administrator for a key (dieplan keys create, or POST /v1/keys). It is kept in this browser only.'),
      el('label', { for: 'api-key-input' }, 'Key'), input,
      el('p', { class: 'actions' }, use, cancel, storedKey() ? forget : ''));
    const dialog = el('dialog', { class: 'editor key-dialog', 'aria-label': 'API key' }, form);
    const finish = (value) => {
      dialog.close();
      dialog.remove();
      pending = null;
      resolve(value);
    };
    form.addEventListener('submit', (event) => {
      event.preventDefault();
      const key = input.value.trim();
      if (!key) return;
      storeKey(key);
      finish(key);
    });
    cancel.addEventListener('click', () => finish(null));
    forget.addEventListener('click', () => { storeKey(''); finish(''); });
    dialog.addEventListener('cancel', (event) => { event.preventDefault(); finish(null); });
    document.body.append(dialog);
    dialog.showModal();
    input.focus();
  });
  return pending;
}

/**
 * Makes a download link (`<a href download>`) work with a key: with a stored key the
 * click fetches the file with it and saves the answer; without one the browser
 * downloads as usual.
 */
export function authorizeDownload(link, fetchText) {
  link.addEventListener('click', async (event) => {
    if (!storedKey()) return;
    event.preventDefault();
    const text = await fetchText(link.getAttribute('href'));
    const url = URL.createObjectURL(new Blob([text], { type: 'text/plain' }));
    const save = el('a', { href: url, download: link.getAttribute('download') || '' });
    document.body.append(save);
    save.click();
    save.remove();
    setTimeout(() => URL.revokeObjectURL(url), 10000);
  });
  return link;
}
