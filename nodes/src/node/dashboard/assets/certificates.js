// The Certificates panel: for each surrogate stream and side, the certificate its fit carries
// (points checked, violations, min/mean/max gap, corrected points), with the fit direction and time.

import { DASH, cell, count, fixed, metres } from './format.js';

export class CertificatesTable {
  constructor(tbody) {
    this.tbody = tbody;
    this.rows = new Map(); // "<stream>/<side>" -> tr
  }

  update(surrogate) {
    for (const surface of surrogate.surfaces) {
      const key = `${surrogate.stream}/${surface.side}`;
      const row = certificateRow(surrogate, surface);
      row.dataset.surface = key;
      const old = this.rows.get(key);
      if (old) old.replaceWith(row);
      else this.tbody.append(row);
      this.rows.set(key, row);
    }
  }
}

function certificateRow(surrogate, { side, certificate: c }) {
  const row = document.createElement('tr');
  const direction = surrogate.direction ? `[${surrogate.direction.map((x) => +x.toFixed(3)).join(', ')}]` : DASH;
  const violations = c ? c.violations : null;
  row.append(
    cell(surrogate.stream, 'name'),
    cell(side),
    cell(direction),
    cell(count(c && c.pointsChecked)),
    cell(count(violations), violations === null ? '' : violations === 0 ? 'good' : 'bad'),
    cell(metres(c && c.minGap)),
    cell(metres(c && c.meanGap)),
    cell(metres(c && c.maxGap)),
    cell(count(c && c.correctedPoints)),
    cell(fixed(surrogate.fitMs, 1)),
  );
  return row;
}
