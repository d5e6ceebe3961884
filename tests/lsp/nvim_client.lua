-- Neovim 0.7's own LSP client against `seqc lsp`: opens the file, waits for its diagnostics,
-- fixes the planted mistake with nvim_buf_set_lines (sent as an incremental change) and waits
-- for them to clear, then stops the server. What it saw goes to SEQC_LSP_OUT, one fact a line;
-- nvim_test.py checks it. Run: nvim --headless -u NONE -c "luafile nvim_client.lua".
local seqc = vim.env.SEQC_BIN
local file = vim.env.SEQC_LSP_FILE
local out = vim.env.SEQC_LSP_OUT
local results = {}
local function say(line) table.insert(results, line) end

local ok, err = pcall(function()
  vim.cmd('edit ' .. vim.fn.fnameescape(file))
  local buf = vim.api.nvim_get_current_buf()
  local client_id = vim.lsp.start_client({
    name = 'seqc',
    cmd = { seqc, 'lsp', '--stdio' },
    root_dir = vim.fn.fnamemodify(file, ':h'),
  })
  say('attached ' .. tostring(vim.lsp.buf_attach_client(buf, client_id)))
  say('published ' .. tostring(vim.wait(10000, function()
    return #vim.diagnostic.get(buf) > 0
  end, 20)))
  for _, d in ipairs(vim.diagnostic.get(buf)) do
    say(string.format('diagnostic %d:%d-%d:%d severity=%d code=%s source=%s %s', d.lnum, d.col,
      d.end_lnum, d.end_col, d.severity, tostring(d.code), tostring(d.source), d.message))
  end
  local line = vim.api.nvim_buf_get_lines(buf, 9, 10, false)[1]
  vim.api.nvim_buf_set_lines(buf, 9, 10, false, { (line:gsub('tme:', 'time:')) })
  say('cleared ' .. tostring(vim.wait(10000, function()
    return #vim.diagnostic.get(buf) == 0
  end, 20)))
  -- Musical time where the text is written: the inlay hints of the first three steps.
  local answers = vim.lsp.buf_request_sync(buf, 'textDocument/inlayHint', {
    textDocument = { uri = vim.uri_from_bufnr(buf) },
    range = { start = { line = 0, character = 0 }, ['end'] = { line = 13, character = 0 } },
  }, 10000)
  for _, answer in pairs(answers or {}) do
    for _, hint in ipairs(answer.result or {}) do
      say(string.format('hint %d %s', hint.position.line, hint.label))
    end
  end
  local client = vim.lsp.get_client_by_id(client_id)
  client.stop()
  say('stopped ' .. tostring(vim.wait(5000, function() return client.is_stopped() end, 20)))
end)
if not ok then say('error ' .. tostring(err)) end
vim.fn.writefile(results, out)
vim.cmd('qa!')
