// report.js: renderer of the clr run report (placeholder until written)
document.body.insertAdjacentHTML('beforeend', '<pre id=status>loading</pre>');
