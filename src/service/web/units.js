// Display units of the page: mm or inch, kept in the browser. The API and the programs
// keep their own units (the API is in mm); only what the page shows is converted.
import { num } from './ui.js';

const KEY = 'dieplan.units';
/** Millimetres per inch (exact, by definition). */
export const MM_PER_INCH = 25.4;

/** The display unit of length: 'mm' or 'inch'. */
export function units() {
  try {
    return localStorage.getItem(KEY) === 'inch' ? 'inch' : 'mm';
  } catch {
    return 'mm';
  }
}

/** Keeps the display unit and redraws the current view. */
export function setUnits(unit) {
  try {
    localStorage.setItem(KEY, unit === 'inch' ? 'inch' : 'mm');
  } catch { /* private mode: this page only */ }
  window.dispatchEvent(new Event('dieplan:refresh'));
}

const inch = () => units() === 'inch';

/** A length given in mm, shown in the display unit (inches get two more decimals). */
export function length(mm, digits = 1) {
  if (typeof mm !== 'number') return num(mm);
  return inch() ? num(mm / MM_PER_INCH, digits + 2, 'in') : num(mm, digits, 'mm');
}

/** A feed given in mm/min, shown in the display unit. */
export function feed(mmMin, digits = 0) {
  if (typeof mmMin !== 'number') return num(mmMin);
  return inch() ? num(mmMin / MM_PER_INCH, digits + 1, 'in/min') : num(mmMin, digits, 'mm/min');
}

/** An area given in mm², shown in the display unit. */
export function area(mm2, digits = 0) {
  if (typeof mm2 !== 'number') return num(mm2);
  return inch() ? num(mm2 / (MM_PER_INCH * MM_PER_INCH), digits + 3, 'in²') : num(mm2, digits, 'mm²');
}

/** The unit's name for column headings: 'mm' or 'in'. */
export function lengthUnit() {
  return inch() ? 'in' : 'mm';
}

/** A coordinate given in mm, in the display unit, without the unit. */
export function coordinate(mm, digits = 2) {
  if (typeof mm !== 'number') return num(mm);
  return inch() ? num(mm / MM_PER_INCH, digits + 2) : num(mm, digits);
}

/** The header's mm/inch switch. */
export function unitsSwitch() {
  const select = document.createElement('select');
  select.id = 'units';
  select.setAttribute('aria-label', 'display units');
  for (const [value, text] of [['mm', 'mm'], ['inch', 'inch']]) {
    const option = document.createElement('option');
    option.value = value;
    option.textContent = text;
    option.selected = units() === value;
    select.append(option);
  }
  select.addEventListener('change', () => setUnits(select.value));
  return select;
}
